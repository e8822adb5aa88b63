#pragma once
/// A generated (fastddsgen 2.x) PubSubType whose getKey() may be called from several threads at
/// once.
///
/// Why: the generated getKey() serialises the key into the type object's own buffer
/// (m_keyBuffer) and hashes it with the type object's own MD5 state (m_md5); a participant
/// registers one type object per type name, and Fast DDS 2.9 calls getKey() from
/// DataWriter::write() on the writing thread without a lock. litamin2d's stream workers write
/// the map patches of different streams (a DataWriter each, one MapPatchPubSubType) at the same
/// time: ThreadSanitizer reported the race (litamin2d under TSan, daemon_replay.sh), and an
/// instance handle hashed from a buffer another thread is filling can be another stream's key.

#include <mutex>

#include <fastdds/rtps/common/InstanceHandle.h>

namespace litamin2::dds {

template <class PubSubType>
class KeyLockedType : public PubSubType {
 public:
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5 = false) override {
    std::lock_guard lock(key_mutex_);
    return PubSubType::getKey(data, handle, force_md5);
  }

 private:
  std::mutex key_mutex_;
};

}  // namespace litamin2::dds

#pragma once
// The raw CDR path of the DDS harnesses: an input's bytes as the serialised payload Fast DDS
// hands to a reader's type (encapsulation header included), deserialised by the reader's
// dds::CheckedType exactly as litamin2d and litamin2-aggregator do.

#include "litamin2/dds/checked_type.hpp"

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstdint>
#include <cstring>

namespace litamin2::fuzz {

/// Deserialises `data` into `msg` with `type`; false when the type refused it (it must never
/// throw: an escaping exception fails the harness).
template <class Type, class Msg>
bool deserialize(Type& type, const std::uint8_t* data, std::size_t size, Msg& msg) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  return type.deserialize(&payload, &msg);
}

}  // namespace litamin2::fuzz

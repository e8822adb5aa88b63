#include "odometry/frame_log.hpp"

#include <filesystem>
#include <stdexcept>

namespace litamin2::tools {

FrameLog::FrameLog(const std::string& path) : out_(path, std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write " + path);
  out_.precision(10);
  out_ << "index,file,stamp_s,status,keyframe,inlier_share,retried,retry_registrations,"
          "recovered,pose_searched,pose_found,map_reset,voxelizations,iterations,"
          "source_distributions,correspondences,self_hits,deskewed,ms,x,y,z\n";
}

void FrameLog::add(std::size_t index, const std::string& file, double stamp_s,
                   const FrameResult& f) {
  const auto t = f.pose.translation();
  out_ << index << ',' << std::filesystem::path(file).filename().string() << ',' << stamp_s << ','
       << (f.registered ? "registered" : "not_registered") << ',' << f.keyframe << ','
       << f.inlier_share << ',' << f.retried << ',' << f.retry_registrations << ',' << f.recovered
       << ',' << f.pose_searched << ',' << f.pose_found << ',' << f.map_reset << ','
       << f.voxelizations << ',' << f.iterations << ',' << f.source_distributions << ','
       << f.correspondences << ',' << f.self_hits << ',' << f.deskewed << ',' << f.times.total_ms()
       << ',' << t.x() << ',' << t.y() << ',' << t.z() << '\n';
}

void FrameLog::add_skipped(std::size_t index, const std::string& file, double stamp_s) {
  out_ << index << ',' << std::filesystem::path(file).filename().string() << ',' << stamp_s
       << ",skipped,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,,,\n";
}

}  // namespace litamin2::tools

#pragma once
/// Building blocks of diagnostic_msgs/DiagnosticStatus messages, shared by the daemon's and the
/// aggregator's status.

#include "diagnostic_msgs/msg/KeyValue.h"

#include <string>

namespace litamin2::dds {

/// One key/value pair of a DiagnosticStatus.
diagnostic_msgs::msg::KeyValue key_value(const std::string& key, const std::string& value);
/// `value` with `decimals` digits after the point (printf's %.*f).
std::string fixed_number(double value, int decimals);

}  // namespace litamin2::dds

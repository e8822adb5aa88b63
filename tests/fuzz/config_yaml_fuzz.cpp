// Fuzz harness: the config loaders on any file, as an operator (or an attacker who can write
// the file) could give it. The first byte picks the loader (litamin2d.yaml, the aggregator's,
// tracker.yaml, mapper.yaml); the rest is the file. Properties: every failure is a ConfigError
// with a message (a yaml-cpp exception escaping is a crash); an accepted config passes its
// validate() again and its tracker sections re-read to the same values.

#include "fuzz_support.hpp"
#include "litamin2/config/aggregator_config_yaml.hpp"
#include "litamin2/config/daemon_config_yaml.hpp"
#include "litamin2/config/mapper_config_yaml.hpp"
#include "litamin2/config/tracker_config_yaml.hpp"
#include "litamin2/core/config_error.hpp"

#include <yaml-cpp/yaml.h>

using namespace litamin2;

namespace {

void check_tracker(const TrackerConfig& config) {
  validate(config);
  const std::string yaml = tracker_config_to_yaml(config);
  LITAMIN2_FUZZ_CHECK(tracker_config_to_yaml(tracker_config_from_yaml(YAML::Load(yaml))) == yaml,
                      "tracker config re-reads to the same values");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || size > 64 * 1024) return 0;
  const std::string file = fuzz::as_file(data + 1, size - 1);
  try {
    switch (data[0] % 4) {
      case 0: {
        const daemon::DaemonConfig c = daemon::load_daemon_config(file);
        daemon::validate(c);
        check_tracker(c.tracker);
        for (const daemon::StreamConfig& s : c.streams) {
          check_tracker(s.tracker);
          fuzz::check_pose(s.extrinsic);
        }
        break;
      }
      case 1: {
        const aggregator::AggregatorConfig c = aggregator::load_aggregator_config(file);
        aggregator::validate(c);
        break;
      }
      case 2:
        check_tracker(load_tracker_config(file));
        break;
      default:
        mapping::validate(mapping::load_mapper_config(file));
        break;
    }
    fuzz::accepted() = true;
  } catch (const ConfigError& e) {
    LITAMIN2_FUZZ_CHECK(e.what()[0] != '\0', "a config error says what is wrong");
  }
  return 0;
}

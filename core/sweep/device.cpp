#include "core/sweep/device.hpp"

namespace dampbound {

const char* to_string(SweepDevice d) {
  switch (d) {
    case SweepDevice::cpu:
      return "cpu";
    case SweepDevice::gpu:
      return "gpu";
    case SweepDevice::automatic:
      return "auto";
  }
  return "?";
}

std::optional<SweepDevice> parse_sweep_device(const std::string& s) {
  for (SweepDevice d : {SweepDevice::cpu, SweepDevice::gpu, SweepDevice::automatic})
    if (s == to_string(d)) return d;
  return std::nullopt;
}

}  // namespace dampbound

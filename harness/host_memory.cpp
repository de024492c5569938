#include "host_memory.h"

#include <fstream>
#include <sstream>

namespace lb {

bool resetHostPeak() {
  std::ofstream f("/proc/self/clear_refs");
  if (!f) return false;
  f << "5";
  f.flush();
  return bool(f);
}

HostPeak hostPeak(bool sinceReset) {
  HostPeak out;
  std::ifstream f("/proc/self/status");
  if (!f) {
    out.reason = "no /proc/self/status (the peak resident set is read from Linux's VmHWM)";
    return out;
  }
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream in(line.substr(6));
    int64_t kb = -1;
    std::string unit;
    if (in >> kb >> unit && unit == "kB" && kb > 0) {
      out.bytes = kb * 1024;
      out.sinceReset = sinceReset;
    } else {
      out.reason = "unreadable VmHWM line in /proc/self/status: '" + line + "'";
    }
    return out;
  }
  out.reason = "/proc/self/status has no VmHWM line";
  return out;
}

}  // namespace lb

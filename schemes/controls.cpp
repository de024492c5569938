// Control schemes for the verdict (compare/suite_verdict.h): twins of sphere whose cost relative to
// it is known. sphere-copy is sphere under another name: it must tie sphere on every workload (a
// verdict between them is a false one). sphere-twice draws every timed frame twice (the copy after
// the statistics query, so its counters and images are sphere's): it must lose to sphere with an
// interval above 1. Listed apart from the compared schemes (schemes/registry.h controlSchemes).
#include "render/scheme.h"
#include "schemes/registry.h"

namespace lb {
namespace {

class SphereTwin : public Scheme {
 public:
  SphereTwin(const std::string& name, const std::string& what, int repeat) {
    info_ = findScheme("sphere")->info();
    info_.name = name;
    info_.description = what;
    info_.seed = "control of sphere (schemes/controls.cpp)";
    info_.drawRepeat = repeat;
  }
  const SchemeInfo& info() const override { return info_; }

 private:
  SchemeInfo info_;
};

}  // namespace

const Scheme& sphereCopyScheme() {
  static const SphereTwin scheme("sphere-copy", "control: sphere under another name (must tie sphere)", 1);
  return scheme;
}

const Scheme& sphereTwiceScheme() {
  static const SphereTwin scheme("sphere-twice",
                                 "control: sphere drawing every timed frame twice (must lose to sphere, ratio ~2)", 2);
  return scheme;
}

}  // namespace lb

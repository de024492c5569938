#include "version.h"

namespace lb {

const char* const kToolVersion = LODBENCH_VERSION;

}  // namespace lb

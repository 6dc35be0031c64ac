#include "plant/device_errors.hpp"

namespace virtcom::plant {

const char* deviceErrorMeaning(int32_t c) {
  switch (c) {
#define X(e, code, meaning) \
  case code: return meaning;
#include "plant/device_errors.def"
#undef X
  }
  return "unknown error code";
}

}  // namespace virtcom::plant

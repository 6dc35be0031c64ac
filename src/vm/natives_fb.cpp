// The standard FBs of bytecode/native_fbs.def for the interpreter: the shared code of
// vm/native_fbs_c.def (which the AOT backend pastes into its generated C) behind the
// NativeFbFn signature of kNativeFbs.
#include "vm/natives.hpp"
#include "vm/value.hpp"

namespace virtcom::vm {

namespace {

// get_FB_MEMBER / set_FB_MEMBER for every member, little endian on any host.
#define FB(name)
#define M(fb, member, offset, ctype)                                                                  \
  inline ctype get_##fb##_##member(const uint8_t* i) { return loadLe<ctype>(i + (offset)); }          \
  inline void set_##fb##_##member(uint8_t* i, ctype v) { storeLe<ctype>(i + (offset), v); }
#include "bytecode/native_fbs.def"
#undef M
#undef FB

#define NATIVE_FBS_C(...) __VA_ARGS__
#include "vm/native_fbs_c.def"
#undef NATIVE_FBS_C

}  // namespace

#define FB(name) \
  bool nativeFb_##name(uint8_t* i, int64_t now) { return fbStep_##name(i, now); }
#define M(fb, member, offset, ctype)
#include "bytecode/native_fbs.def"
#undef M
#undef FB

}  // namespace virtcom::vm

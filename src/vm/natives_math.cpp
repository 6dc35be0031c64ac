// Math and bit-rotation natives: pure functions of their register arguments (the rotations
// from vm/natives_pure_c.def, shared with the AOT backend).
#include <cmath>

#include "vm/natives.hpp"
#include "vm/value.hpp"

namespace virtcom::vm {

using bc::FaultKind;

namespace {

template <double (*F)(double)>
FaultKind unary(uint64_t* a) {
  a[0] = fromF(F(asF(a[0])));
  return FaultKind::None;
}

double sqrtD(double x) { return std::sqrt(x); }
double lnD(double x) { return std::log(x); }
double logD(double x) { return std::log10(x); }
double expD(double x) { return std::exp(x); }
double sinD(double x) { return std::sin(x); }
double cosD(double x) { return std::cos(x); }
double tanD(double x) { return std::tan(x); }
double asinD(double x) { return std::asin(x); }
double acosD(double x) { return std::acos(x); }
double atanD(double x) { return std::atan(x); }
double fabsD(double x) { return std::fabs(x); }
double truncD(double x) { return std::trunc(x); }

#define NATIVES_PURE_C(...) __VA_ARGS__
#define PURE_NATIVE(name)
#include "vm/natives_pure_c.def"
#undef PURE_NATIVE
#undef NATIVES_PURE_C

}  // namespace

FaultKind native_SQRT(uint64_t* a, const NativeContext&) { return unary<sqrtD>(a); }
FaultKind native_LN(uint64_t* a, const NativeContext&) { return unary<lnD>(a); }
FaultKind native_LOG(uint64_t* a, const NativeContext&) { return unary<logD>(a); }
FaultKind native_EXP(uint64_t* a, const NativeContext&) { return unary<expD>(a); }
FaultKind native_SIN(uint64_t* a, const NativeContext&) { return unary<sinD>(a); }
FaultKind native_COS(uint64_t* a, const NativeContext&) { return unary<cosD>(a); }
FaultKind native_TAN(uint64_t* a, const NativeContext&) { return unary<tanD>(a); }
FaultKind native_ASIN(uint64_t* a, const NativeContext&) { return unary<asinD>(a); }
FaultKind native_ACOS(uint64_t* a, const NativeContext&) { return unary<acosD>(a); }
FaultKind native_ATAN(uint64_t* a, const NativeContext&) { return unary<atanD>(a); }
FaultKind native_FABS(uint64_t* a, const NativeContext&) { return unary<fabsD>(a); }
FaultKind native_FTRUNC(uint64_t* a, const NativeContext&) { return unary<truncD>(a); }

FaultKind native_ATAN2(uint64_t* a, const NativeContext&) {
  a[0] = fromF(std::atan2(asF(a[0]), asF(a[1])));
  return FaultKind::None;
}

FaultKind native_EXPT(uint64_t* a, const NativeContext&) {
  a[0] = fromF(std::pow(asF(a[0]), asF(a[1])));
  return FaultKind::None;
}

// The pure natives: the shared code of vm/natives_pure_c.def behind the NativeFn signature.
#define NATIVES_PURE_C(...)
#define PURE_NATIVE(name)                                     \
  FaultKind native_##name(uint64_t* a, const NativeContext&) { \
    a[0] = pureNative_##name(a);                              \
    return FaultKind::None;                                   \
  }
#include "vm/natives_pure_c.def"
#undef PURE_NATIVE
#undef NATIVES_PURE_C

}  // namespace virtcom::vm

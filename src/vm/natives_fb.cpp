// The standard FBs of bytecode/native_fbs.def in C++. Each function mirrors its FB's ST body
// in lang/st/prelude.cpp operation for operation (BOOLs are bytes tested for != 0 and combined
// bitwise, as the compiled ST does), so the native and the ST body agree on every input,
// including BOOL bytes other than 0 and 1 written through pointers.
#include <type_traits>

#include "vm/natives.hpp"
#include "vm/value.hpp"

namespace virtcom::vm {

namespace {

// One type per member, named FB_MEMBER, carrying its C type and offset: get<TON_PT>(instance).
#define FB(name)
#define M(fb, member, offset, ctype)            \
  struct fb##_##member {                        \
    using T = ctype;                            \
    static constexpr uint32_t kOffset = offset; \
  };
#include "bytecode/native_fbs.def"
#undef M
#undef FB

template <class F>
typename F::T get(const uint8_t* instance) {
  return loadLe<typename F::T>(instance + F::kOffset);
}
template <class F>
void set(uint8_t* instance, std::type_identity_t<typename F::T> v) {
  storeLe<typename F::T>(instance + F::kOffset, v);
}

// LTIME_TO_TIME(now - start): ns to ms toward zero, wrapped to TIME's 32 bits.
int32_t elapsedMs(int64_t nowNs, int64_t startNs) {
  const int64_t ns = asI(fromI(nowNs) - fromI(startNs));
  return static_cast<int32_t>(ns / 1'000'000);
}

// IF NOT running THEN running := TRUE; startNs := now; END_IF
template <class Running, class Start>
void startOnce(uint8_t* i, int64_t now) {
  if (get<Running>(i) == 0) {
    set<Running>(i, 1);
    set<Start>(i, now);
  }
}

// TOF and TP while running:
// IF elapsed >= PT THEN Q := FALSE; ET := PT; running := FALSE; ELSE ET := elapsed; END_IF
template <class PT, class Q, class ET, class Start, class Running>
void runOut(uint8_t* i, int64_t now) {
  const int32_t elapsed = elapsedMs(now, get<Start>(i));
  if (elapsed >= get<PT>(i)) {
    set<Q>(i, 0);
    set<ET>(i, get<PT>(i));
    set<Running>(i, 0);
  } else {
    set<ET>(i, elapsed);
  }
}

}  // namespace

bool nativeFb_TON(uint8_t* i, int64_t now) {
  if (get<TON_IN>(i) == 0) {
    set<TON_RUNNING>(i, 0);
    set<TON_Q>(i, 0);
    set<TON_ET>(i, 0);
    return false;
  }
  startOnce<TON_RUNNING, TON_STARTNS>(i, now);
  const int32_t elapsed = elapsedMs(now, get<TON_STARTNS>(i));
  const bool done = elapsed >= get<TON_PT>(i);
  set<TON_Q>(i, done);
  set<TON_ET>(i, done ? get<TON_PT>(i) : elapsed);
  return true;
}

bool nativeFb_TOF(uint8_t* i, int64_t now) {
  if (get<TOF_IN>(i) != 0) {
    set<TOF_Q>(i, 1);
    set<TOF_ET>(i, 0);
    set<TOF_RUNNING>(i, 0);
    return false;
  }
  if (get<TOF_Q>(i) == 0) return false;
  startOnce<TOF_RUNNING, TOF_STARTNS>(i, now);
  runOut<TOF_PT, TOF_Q, TOF_ET, TOF_STARTNS, TOF_RUNNING>(i, now);
  return true;
}

bool nativeFb_TP(uint8_t* i, int64_t now) {
  bool readTime = false;
  if (((get<TP_RUNNING>(i) == 0) & get<TP_IN>(i) & (get<TP_PREVIN>(i) == 0)) != 0) {
    set<TP_RUNNING>(i, 1);
    set<TP_STARTNS>(i, now);
    set<TP_Q>(i, 1);
    readTime = true;
  }
  if (get<TP_RUNNING>(i) != 0) {
    runOut<TP_PT, TP_Q, TP_ET, TP_STARTNS, TP_RUNNING>(i, now);
    readTime = true;
  }
  if (((get<TP_RUNNING>(i) == 0) & (get<TP_IN>(i) == 0)) != 0) set<TP_ET>(i, 0);
  set<TP_PREVIN>(i, get<TP_IN>(i));
  return readTime;
}

bool nativeFb_CTU(uint8_t* i, int64_t) {
  if (get<CTU_RESET>(i) != 0) {
    set<CTU_CV>(i, 0);
  } else if ((get<CTU_CU>(i) & (get<CTU_PREVCU>(i) == 0) & (get<CTU_CV>(i) < 32767)) != 0) {
    set<CTU_CV>(i, static_cast<int16_t>(get<CTU_CV>(i) + 1));
  }
  set<CTU_Q>(i, get<CTU_CV>(i) >= get<CTU_PV>(i));
  set<CTU_PREVCU>(i, get<CTU_CU>(i));
  return false;
}

bool nativeFb_CTD(uint8_t* i, int64_t) {
  if (get<CTD_LOAD>(i) != 0) {
    set<CTD_CV>(i, get<CTD_PV>(i));
  } else if ((get<CTD_CD>(i) & (get<CTD_PREVCD>(i) == 0) & (get<CTD_CV>(i) > -32768)) != 0) {
    set<CTD_CV>(i, static_cast<int16_t>(get<CTD_CV>(i) - 1));
  }
  set<CTD_Q>(i, get<CTD_CV>(i) <= 0);
  set<CTD_PREVCD>(i, get<CTD_CD>(i));
  return false;
}

bool nativeFb_CTUD(uint8_t* i, int64_t) {
  if (get<CTUD_RESET>(i) != 0) {
    set<CTUD_CV>(i, 0);
  } else if (get<CTUD_LOAD>(i) != 0) {
    set<CTUD_CV>(i, get<CTUD_PV>(i));
  } else {
    if ((get<CTUD_CU>(i) & (get<CTUD_PREVCU>(i) == 0) & (get<CTUD_CV>(i) < 32767)) != 0)
      set<CTUD_CV>(i, static_cast<int16_t>(get<CTUD_CV>(i) + 1));
    if ((get<CTUD_CD>(i) & (get<CTUD_PREVCD>(i) == 0) & (get<CTUD_CV>(i) > -32768)) != 0)
      set<CTUD_CV>(i, static_cast<int16_t>(get<CTUD_CV>(i) - 1));
  }
  set<CTUD_QU>(i, get<CTUD_CV>(i) >= get<CTUD_PV>(i));
  set<CTUD_QD>(i, get<CTUD_CV>(i) <= 0);
  set<CTUD_PREVCU>(i, get<CTUD_CU>(i));
  set<CTUD_PREVCD>(i, get<CTUD_CD>(i));
  return false;
}

bool nativeFb_R_TRIG(uint8_t* i, int64_t) {
  set<R_TRIG_Q>(i, get<R_TRIG_CLK>(i) & (get<R_TRIG_M>(i) == 0));
  set<R_TRIG_M>(i, get<R_TRIG_CLK>(i));
  return false;
}

bool nativeFb_F_TRIG(uint8_t* i, int64_t) {
  set<F_TRIG_Q>(i, (get<F_TRIG_CLK>(i) == 0) & (get<F_TRIG_M>(i) == 0));
  set<F_TRIG_M>(i, get<F_TRIG_CLK>(i) == 0);
  return false;
}

bool nativeFb_SR(uint8_t* i, int64_t) {
  set<SR_Q1>(i, get<SR_SET1>(i) | ((get<SR_RESET>(i) == 0) & get<SR_Q1>(i)));
  return false;
}

bool nativeFb_RS(uint8_t* i, int64_t) {
  set<RS_Q1>(i, (get<RS_RESET1>(i) == 0) & (get<RS_SET>(i) | get<RS_Q1>(i)));
  return false;
}

}  // namespace virtcom::vm

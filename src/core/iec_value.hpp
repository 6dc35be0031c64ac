#pragma once
// IEC 61131-3 elementary types and the textual (IEC literal) form of their values.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace virtcom {

enum class ElemKind : uint8_t { Bool, Bits, Signed, Unsigned, Float, Duration, Date, Text, Char };

enum class ElemType : uint8_t {
#define X(e, name, size, kind) e,
#include "core/elementary_types.def"
#undef X
};

struct ElemTypeInfo {
  std::string_view name;
  uint32_t sizeBytes;  // 0 for STRING/WSTRING: their size depends on the declared length
  ElemKind kind;
};

// Inline: the wiring and the VM ask per value, on hot paths.
inline constexpr ElemTypeInfo kElemTypeInfo[] = {
#define X(e, name, size, kind) {name, size, ElemKind::kind},
#include "core/elementary_types.def"
#undef X
};
inline const ElemTypeInfo& elemTypeInfo(ElemType t) { return kElemTypeInfo[static_cast<size_t>(t)]; }
// Looks up a type keyword (case-insensitive), accepting the aliases TOD, DT, LTOD and LDT.
// False if unknown.
bool elemTypeByName(std::string_view name, ElemType& out);

bool isIntegerKind(ElemKind k);  // Bits, Signed, Unsigned
inline bool isInteger(ElemType t) { return isIntegerKind(elemTypeInfo(t).kind); }
inline bool isSignedInt(ElemType t) { return elemTypeInfo(t).kind == ElemKind::Signed; }
// Held as an unsigned number: bit strings, unsigned integers, CHAR/WCHAR (their code).
inline bool isZeroExtendedKind(ElemKind k) { return k == ElemKind::Bits || k == ElemKind::Unsigned || k == ElemKind::Char; }
inline bool isFloat(ElemType t) { return elemTypeInfo(t).kind == ElemKind::Float; }
// Number of value bits of an integer or bit-string type (BOOL: 1).
uint32_t bitWidth(ElemType t);
// Nanoseconds per stored unit of a duration, date or time of day (TIME 1e6, DT 1e9, LDT 1);
// 0 for every other type. Conversions and date arithmetic scale by it.
int64_t timeUnitNs(ElemType t);
// Which part of a point in time a date type holds: DATE/LDATE the day, TOD/LTOD the clock,
// DT/LDT both; None for the rest.
enum class DatePart : uint8_t { None, Day, Clock, Both };
DatePart datePart(ElemType t);

// IEC literal forms, as `virtcom exec --print` shows values.
std::string formatTimeMs(int64_t ms);        // T#1s500ms, T#0ms, T#-2s
std::string formatLtimeNs(int64_t ns);       // LTIME#1s5ns
std::string formatDate(int64_t secondsSince1970);      // D#2024-01-02
std::string formatTimeOfDay(int64_t msSinceMidnight);  // TOD#12:30:00.5
std::string formatDateAndTime(int64_t secondsSince1970);  // DT#2024-01-02-12:30:00
std::string formatLdate(int64_t nsSince1970);     // LDATE#2024-01-02
std::string formatLtod(int64_t nsSinceMidnight);  // LTOD#12:30:00.000000005
std::string formatLdt(int64_t nsSince1970);       // LDT#2024-01-02-12:30:00.5
std::string formatReal(float v);    // shortest round-trip form with a decimal point: 1.5, 2.0, 1E+20
std::string formatLreal(double v);
// The same texts written into `buf` (at least kIecTextMax bytes) without allocating, for the
// VM's *_TO_STRING conversions; each returns the length.
inline constexpr size_t kIecTextMax = 64;
size_t formatTimeMsInto(char* buf, int64_t ms);
size_t formatLtimeNsInto(char* buf, int64_t ns);
size_t formatDateInto(char* buf, int64_t secondsSince1970);
size_t formatTimeOfDayInto(char* buf, int64_t msSinceMidnight);
size_t formatDateAndTimeInto(char* buf, int64_t secondsSince1970);
size_t formatLdateInto(char* buf, int64_t nsSince1970);
size_t formatLtodInto(char* buf, int64_t nsSinceMidnight);
size_t formatLdtInto(char* buf, int64_t nsSince1970);
size_t formatRealInto(char* buf, float v);
size_t formatLrealInto(char* buf, double v);
// Quotes a STRING value with IEC $-escapes: 'it$'s'.
std::string quoteString(std::string_view raw);

// Days since 1970-01-01 for a proleptic Gregorian date and back (used by D#/DT# literals).
int64_t daysFromCivil(int64_t y, unsigned m, unsigned d);
void civilFromDays(int64_t days, int64_t& y, unsigned& m, unsigned& d);

}  // namespace virtcom

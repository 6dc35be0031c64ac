#pragma once
// The declarative mapping between the UNIVERSAL_AXIS block (lib/universal_axis.st) and one drive
// telegram. A mapping file (lib/mappings/*.yaml, format in docs/universal-axis.md, Mapping files)
// names a telegram of telegrams.def and binds the block's Control_* signals to bits, multi-bit
// fields and words of the telegram's output words, its Status_* signals to the input words,
// and may set Cfg_* block inputs to constants. parseMapping() validates everything at load;
// MappingRuntime applies a mapping every tick without allocating or looking anything up.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/config_node.hpp"
#include "core/iec_value.hpp"
#include "drives/telegram.hpp"

namespace virtcom::drives {

enum class AxisSignal : uint8_t {
#define VIRTCOM_AXIS_SIGNAL(id, type, kind, required, doc) id,
#include "drives/axis_signals.def"
};
inline constexpr size_t kAxisSignalCount = 0
#define VIRTCOM_AXIS_SIGNAL(id, type, kind, required, doc) +1
#include "drives/axis_signals.def"
    ;

enum class SignalKind : uint8_t { Control, Status, Config };

struct AxisSignalDef {
  AxisSignal id;
  std::string_view name;
  ElemType type;
  SignalKind kind;
  bool required;
  std::string_view doc;
};

std::span<const AxisSignalDef> axisSignals();
inline const AxisSignalDef& axisSignal(AxisSignal s) { return axisSignals()[static_cast<size_t>(s)]; }
// By exact name, or by a thesis alias (Status_WarningCode -> Status_AlarmCode); null if unknown.
const AxisSignalDef* findAxisSignal(std::string_view name);

// Bits [lsb, lsb + width) of one word of one direction; width 0 = the whole word.
struct WordBits {
  uint8_t word = 0;
  uint8_t lsb = 0;
  uint8_t width = 0;
};

// raw = value * num / den + offset (outputs); value = (raw - offset) * den / num (inputs).
struct Scale {
  double num = 1, den = 1, offset = 0;
};

struct OutputRule {
  enum class Kind : uint8_t { Bit, Field, Word, Const };
  Kind kind = Kind::Bit;
  AxisSignal signal{};  // Bit, Word
  WordBits at;
  bool invert = false;
  bool pulseRising = false;        // 1 for one tick on the signal's 0 -> 1 edge
  bool zeroBeforeOne = false;      // 0 in the first frame (the drive needs 0 -> 1, e.g. S1 -> S2)
  static constexpr size_t kMaxCodes = 4;
  std::array<AxisSignal, kMaxCodes> codeSignals{};  // Field: the first TRUE source selects its code
  std::array<uint32_t, kMaxCodes> codes{};
  uint8_t codeCount = 0;
  uint32_t value = 0;              // Const value, Field default code
  Scale scale;                     // Word
  double lo = 0, hi = 0;           // Word: clamp, in raw units (defaults: the word's range)
  int16_t signedFrom = -1;         // Word: AxisSignal whose TRUE negates the value
};

struct InputRule {
  enum class Kind : uint8_t { Bit, Field, Word };
  Kind kind = Kind::Bit;
  AxisSignal signal{};
  WordBits at;
  bool invert = false;
  Scale scale;
  int16_t signedBy = -1;           // Word: a Status Bool; FALSE negates (magnitude + direction bit)
};

struct MappingSpec {
  TelegramId telegram{};
  ByteOrder order = ByteOrder::Big;  // wire byte order the block side writes/reads
  std::vector<OutputRule> outputs;
  std::vector<InputRule> inputs;
  std::vector<std::pair<AxisSignal, double>> blockInputs;  // Cfg_* constants
  std::optional<WordBits> masterSignOfLife;                // generated 1..15, 0 skipped
  std::array<bool, kAxisSignalCount> bound{};              // has a rule, a constant or is `unavailable`
  std::array<bool, kAxisSignalCount> unavailable{};        // listed under `unavailable:`
  // The drive reference speeds (p2000, rpm) the mapping assumes, where it states one: `params:
  // ref_speed` (the named scales) and `block_inputs: Cfg_RefSpeed` (the block's feedback).
  struct ReferenceSpeed {
    const char* key;
    double rpm;
    SourceLocation loc;
  };
  std::vector<ReferenceSpeed> referenceSpeeds;
};

// Validates a parsed mapping file. Every problem is reported through `diags` with the file
// position (unknown telegram or word, bit out of range, a bit written twice, a signal mapped
// twice, width/type mismatch, a required signal neither mapped nor `unavailable`); returns
// nullopt if there was any.
std::optional<MappingSpec> parseMapping(const ConfigNode& root, Diagnostics& diags);

// Signal values in block units (BOOL as 0/1), indexed by AxisSignal.
using AxisSignalValues = std::array<double, kAxisSignalCount>;

// Applies one mapping. Per-tick, never allocates (the constructor does, at load time).
class MappingRuntime {
 public:
  explicit MappingRuntime(const MappingSpec& spec);
  const MappingSpec& spec() const { return *spec_; }
  // Control_* values -> the telegram's output words (ToDrive), then the wire image in the
  // mapping's byte order. Advances the pulse/interlock state and the master sign-of-life.
  void pack(const AxisSignalValues& values, RawWords& words);
  // True when packing the same values again would give the same words but for the master
  // sign-of-life: no pulse fired in the last pack() and the first frame is past.
  bool repeatable() const { return repeatable_; }
  // What pack() does to words it packed before when the values have not changed since and
  // repeatable() holds: only the master sign-of-life advances. Returns the word it changed
  // (bit i = word i; 0 without a sign-of-life).
  uint32_t advanceSignOfLife(RawWords& words);
  void toWire(const RawWords& words, std::span<uint8_t> image) const;
  // The words the drive decodes (telegram byte order) from the image toWire() writes, without
  // the image: per word a truncation to its width and, if the byte orders differ, a byte swap.
  // Only the words in `changedWords` (bit i = word i); the others in `rx` are left as they are.
  void toDrive(const RawWords& words, RawWords& rx, uint32_t changedWords) const;
  // The telegram's input words (FromDrive) -> Status_* values (only bound ones are written).
  void unpack(const RawWords& words, AxisSignalValues& values) const;
  // The same for the rules that read a word in `changedWords` (bit i = input word i); the other
  // values are left as they are, which is what unpack() would give them if their words have not
  // changed since.
  void unpack(const RawWords& words, AxisSignalValues& values, uint32_t changedWords) const;
  void fromWire(std::span<const uint8_t> image, RawWords& words) const;
  // fromWire() of the drive's reply `tx` encoded in the telegram's byte order, without the
  // image, into `words`; returns the words that changed (bit i = word i).
  uint32_t fromDrive(const RawWords& tx, RawWords& words) const;

 private:
  // Per input rule, computed once: the words it reads (bit i = word i), its word's wire type, and
  // whether its scale is 1:1 ((raw - 0) * 1 / 1 is raw: no division per tick).
  struct InputPlan {
    uint32_t words;
    WireType type;
    bool identity;
  };
  // Per word of one direction: 16-bit words are truncated on the wire.
  struct WordWidths {
    std::array<bool, kMaxWords> wide{};
    size_t count = 0;
  };
  static WordWidths widths(TelegramId t, Dir d);

  const MappingSpec* spec_;
  bool swap_;  // the mapping's byte order is not the telegram's
  WordWidths toDrive_, fromDrive_;
  std::vector<InputPlan> inputs_;
  std::array<bool, kAxisSignalCount> previous_{};
  std::array<bool, kAxisSignalCount> seenZero_{};
  uint8_t signOfLife_ = 0;
  bool packed_ = false, repeatable_ = false;
};

}  // namespace virtcom::drives

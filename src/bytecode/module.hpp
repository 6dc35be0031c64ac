#pragma once
// The program image: what the compiler produces and the VM/PLC runtime execute.
// Everything a tool needs to run the program, address its variables by name (CLI, ADS, Modbus)
// and map a fault back to the source lives here; nothing here depends on the compiler.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bytecode/instruction.hpp"
#include "core/coverage.hpp"
#include "core/iec_value.hpp"
#include "core/source.hpp"

namespace virtcom::bc {

using TypeId = uint32_t;
inline constexpr TypeId kNoType = 0xffffffffu;

enum class TypeKind : uint8_t {
  Elementary,     // elem
  String,         // elem = String or Wstring, stringLength characters
  Array,          // element, dims
  Struct,         // fields (also the layout of FB, PROGRAM and CLASS instances)
  Enum,           // elem = base integer type, enumerators
  Pointer,        // element = pointee (kNoType for POINTER TO ANY / PVOID)
  Reference,      // element = referee
};

struct ArrayDim {
  int64_t lo = 0;
  int64_t hi = 0;
  uint64_t count() const { return static_cast<uint64_t>(hi - lo + 1); }
};

struct Field {
  std::string name;   // as declared (case preserved)
  TypeId type = kNoType;
  uint32_t offset = 0;     // bytes from the start of the struct
  int8_t bit = -1;         // >= 0: a BOOL packed as one bit (located %IX/%QX variables)
  bool hidden = false;     // internal state (e.g. a timer's start time): not listed, still addressable
  bool readOnly = false;   // CONSTANT, or {attribute 'ads_readonly'}
  bool absolute = false;   // offset is a memory address: a located (AT %IX0.0) member of a POU
  std::string section;     // "VAR_INPUT", "VAR_OUTPUT", "VAR", ... for tools that show interfaces
  bool retain = false;     // RETAIN or PERSISTENT: kept over a warm start
};

struct Enumerator {
  std::string name;
  int64_t value = 0;
};

struct TypeDesc {
  TypeKind kind = TypeKind::Elementary;
  std::string name;         // IEC name, e.g. "INT", "STRING(80)", "ARRAY [1..3] OF INT", "TON", "MAIN"
  uint32_t size = 0;        // bytes
  uint32_t align = 1;
  ElemType elem = ElemType::Bool;
  TypeId element = kNoType;
  std::vector<ArrayDim> dims;
  std::vector<Field> fields;
  std::vector<Enumerator> enumerators;
  uint32_t stringLength = 0;
};

enum class PouKind : uint8_t { Program, Function, FunctionBlock, Method, Action, PropertyGet, PropertySet, Init };

struct PouInfo {
  std::string name;            // qualified: "MAIN", "FB_Motor.Start", "FB_Motor.Speed.GET"
  PouKind kind = PouKind::Function;
  uint32_t codeStart = 0;      // index of the first instruction
  uint32_t codeSize = 0;
  uint16_t numRegs = 2;        // register window size (>= 2: fp and this)
  uint32_t frameSize = 0;      // bytes of stack (locals, temps, inputs of functions)
  uint32_t frameTemplate = 0;  // address in static memory of frameSize bytes of initial values
  TypeId instanceType = kNoType;  // FB/PROGRAM instance layout
};

// One array dimension as INDEX sees it: an index i is valid if lo <= i < lo + count, and
// selects the element (i - lo) * stride bytes after the start.
struct IndexDesc {
  int64_t lo = 0;
  uint32_t count = 1;
  uint32_t stride = 1;

  // The largest byte offset INDEX yields with this description, (count - 1) * stride: it faults
  // for an index outside lo .. lo + count - 1, so an element's address (the array's base plus
  // INDEX) lies at most this far past the base. 0 for an empty array, whose INDEX always faults.
  uint64_t lastOffset() const { return count ? uint64_t{count - 1} * stride : 0; }
};

// One entry per instruction that starts a statement (sorted by pc).
struct LineEntry {
  uint32_t pc = 0;
  SourceLocation loc;
};

// A name visible from outside: a global variable, or a program instance (whose members are
// reached through its struct type).
struct Symbol {
  std::string name;      // "GVL.x", "x" for a global without list name, "MAIN"
  TypeId type = kNoType;
  uint32_t address = 0;
  bool readOnly = false;
  bool retain = false;   // a RETAIN or PERSISTENT global: kept over a warm start
  int8_t bit = -1;       // a located BOOL (AT %IX0.2): the bit of the byte at `address`
};

struct ProgramInstance {
  std::string name;      // instance name, e.g. "MAIN"
  uint32_t pou = 0;      // the PROGRAM's body
  uint32_t address = 0;  // instance memory
};

struct TaskInfo {
  std::string name;
  int64_t intervalNs = 10'000'000;
  int32_t priority = 0;
  std::vector<uint32_t> programs;  // indices into Module::programs, in call order
  // The compiler's implicit task (`MainTask` or `__DEFAULT`), not one a TASK declares: the
  // cycle time of `--cycle-time` or a cell's `plc.cycle_time` replaces its interval.
  bool isDefault = false;
};

// Process image areas (%I, %Q, %M): fixed regions of the memory image.
struct ProcessArea {
  uint32_t address = 0;
  uint32_t size = 0;
};

// One coverage probe (docs/coverage.md): a COVER instruction the compiler placed when asked to
// (st::CompileOptions::coverage), and what its counter counts.
struct CoverageProbe {
  uint32_t pou = 0;       // index into Module::pous
  SourceLocation loc;     // the statement; for a branch its IF/CASE; for SFC the step/transition
  CoverageKind kind = CoverageKind::Statement;
  uint16_t arm = 0;       // Branch: the arm's index in its decision
  uint16_t arms = 0;      // Branch: how many arms the decision has (an implicit ELSE counts)
  std::string name;       // Step, Transition: the element's name
};

// The probes of a module and their counters: probe i counts in the 8 bytes (u64, little endian)
// at counterAddress + 8 * i of the memory image, zero in the initial image and kept over a cold
// start (vm::Machine::coldStart), so a run restarted (power loss) keeps counting.
struct CoverageTable {
  uint32_t counterAddress = 0;
  std::vector<CoverageProbe> probes;  // empty: compiled without coverage
  static constexpr uint32_t kNoCounter = 0xffffffffu;
  // The probe whose counter is at `address`, or kNoCounter.
  uint32_t counterAt(uint32_t address) const {
    if (address < counterAddress || (address - counterAddress) % 8 != 0) return kNoCounter;
    const uint32_t i = (address - counterAddress) / 8;
    return i < probes.size() ? i : kNoCounter;
  }
  uint32_t counterBytes() const { return static_cast<uint32_t>(probes.size() * 8); }
};

struct Module {
  std::vector<Instr> code;
  std::vector<uint64_t> constants;
  std::vector<IndexDesc> indexes;  // INDEX's C
  std::vector<PouInfo> pous;
  std::vector<LineEntry> lines;
  std::vector<std::string> files;    // fileId -> path for LineEntry locations

  std::vector<TypeDesc> types;
  std::vector<Symbol> symbols;
  std::vector<ProgramInstance> programs;
  std::vector<TaskInfo> tasks;

  // Memory image: [0, kNullGuard) never addressable; then read-only data (frame templates,
  // string literals), the process image areas, globals and program instances (all initialised
  // from initialImage), then the stack.
  static constexpr uint32_t kNullGuard = 16;
  std::vector<uint8_t> initialImage;  // bytes [0, staticSize)
  uint32_t staticSize = 0;
  uint32_t writableEnd = 0;  // [kNullGuard, writableEnd) holds variables; above it only constant data
  uint32_t stackSize = 64 * 1024;
  uint32_t maxCallDepth = 256;
  uint32_t registerStackSize = 16 * 1024;  // total registers across all active windows
  ProcessArea inputs, outputs, memory;
  // Init POU run once at cold start after the image is loaded (FB_init calls); kNoPou if none.
  static constexpr uint32_t kNoPou = 0xffffffffu;
  uint32_t initPou = kNoPou;
  // Exit POU run once when the program ends (FB_exit calls); kNoPou if none. Kind Init too:
  // both run outside the scan, without coverage.
  uint32_t exitPou = kNoPou;
  CoverageTable coverage;

  uint32_t memorySize() const { return staticSize + stackSize; }
  // Source location of the statement containing pc, or an empty location.
  SourceLocation locationOf(uint32_t pc) const;
  // Index of the POU whose code contains pc, or kNoPou.
  uint32_t pouAt(uint32_t pc) const;
};

// A resolved variable: where it lives and what it is.
struct VarRef {
  TypeId type = kNoType;
  uint32_t address = 0;
  int8_t bit = -1;
  bool readOnly = false;
};

// Resolves a qualified, case-insensitive name such as "MAIN.robot[2].busy", "GVL.x", "x" or
// "MAIN.w.3" (bit of an integer) to its address. Returns nullopt if any part does not exist
// or an index is out of range. Allocates (string work): not for the scan path.
std::optional<VarRef> resolveVariable(const Module& m, std::string_view path);

// The IEC literal form of the value at `ref` in `memory` (e.g. 42, TRUE, T#1s500ms, 'abc',
// Color#Red, [1, 2, 3], (x := 1, y := 2)). Defined in value_print.cpp.
std::string formatValue(const Module& m, const VarRef& ref, const uint8_t* memory);

// Parses an IEC literal (42, -7, 16#FF, 1.5, TRUE, T#1s, 'text', Color#Red, Red) of the type at
// `ref` and writes it into `memory`. Returns an error message, empty on success. Defined in
// value_parse.cpp, which reads time, date and integer text with core/iec_literal.
std::string writeValueFromText(const Module& m, const VarRef& ref, std::string_view text, uint8_t* memory);

}  // namespace virtcom::bc

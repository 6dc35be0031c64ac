#pragma once
// What the ADS server knows about the PLC program: its symbols, their data types and the layout
// of the memory image they live in. The server sees only this (never the compiler or the VM):
// an adapter builds it from the program image (proto/ads/plc/module_symbols.hpp).
// Names are matched case-insensitively, as TwinCAT identifiers are.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace virtcom::proto::ads {

// ADS data type ids (ADST_*, docs/ads.md, Wire reference: ADS data type ids and flags).
namespace adst {
inline constexpr uint32_t kVoid = 0, kInt16 = 2, kInt32 = 3, kReal32 = 4, kReal64 = 5, kInt8 = 16, kUint8 = 17,
                          kUint16 = 18, kUint32 = 19, kInt64 = 20, kUint64 = 21, kString = 30, kWstring = 31,
                          kBit = 33, kBigType = 65;
}

// Symbol flags (ADSSYMBOLFLAG_*) and data type flags (ADSDATATYPEFLAG_*) the server uses
// (docs/ads.md, ADS data type ids and flags).
inline constexpr uint16_t kSymbolFlagBitValue = 0x0002;
inline constexpr uint16_t kSymbolFlagReadOnly = 0x0020;
inline constexpr uint32_t kTypeFlagDataType = 0x1;
inline constexpr uint32_t kTypeFlagDataItem = 0x2;
inline constexpr uint32_t kTypeFlagEnumInfos = 0x2000;

struct ArrayBounds {
  int32_t lowerBound = 0;
  uint32_t elementCount = 0;
};

struct DataType {
  struct Member {
    std::string name;
    std::string type;  // a DataType name
    uint32_t size = 0;
    uint32_t offset = 0;  // bytes from the start of the parent
    uint32_t adsType = adst::kVoid;
  };
  struct Enumerator {
    std::string name;
    int64_t value = 0;
  };
  std::string name;      // "INT", "ST_Point", "ARRAY [0..2] OF INT", "STRING(80)", "E_Mode"
  std::string baseType;  // arrays: the element type; enums: the integer type; else ""
  uint32_t size = 0;
  uint32_t adsType = adst::kVoid;
  uint32_t flags = kTypeFlagDataType;
  std::vector<ArrayBounds> dims;
  std::vector<Member> members;
  std::vector<Enumerator> enumerators;
};

// One variable as ADS addresses it.
struct Symbol {
  std::string name;  // "MAIN.count", "GVL.x"
  std::string type;  // a DataType name
  uint32_t indexGroup = 0;
  uint32_t indexOffset = 0;
  uint32_t size = 0;
  uint32_t adsType = adst::kVoid;
  uint16_t flags = 0;  // kSymbolFlagReadOnly, kSymbolFlagBitValue
};

// A byte range of the data area.
struct ByteRange {
  uint32_t offset = 0;
  uint32_t size = 0;
};

// Where things are in the data area (index group 0x4040, IO = byte offset): the process image
// areas %I, %Q, %M are sub-ranges of it, so one snapshot serves every group.
struct MemoryLayout {
  uint32_t dataSize = 0;
  ByteRange inputs, outputs, memory;
  std::vector<ByteRange> readOnly;  // CONSTANTs and {attribute 'ads_readonly'} variables
};

class SymbolTable {
 public:
  // Resolves any path (a listed symbol, or a member / element / bit below one) to a symbol.
  using Resolver = std::function<std::optional<Symbol>(std::string_view path)>;

  // `symbols` are what the symbol upload lists; `types` every type they use (recursively).
  SymbolTable(std::vector<Symbol> symbols, std::vector<DataType> types, MemoryLayout layout, Resolver resolver);

  std::span<const Symbol> symbols() const { return symbols_; }
  std::span<const DataType> types() const { return types_; }
  const MemoryLayout& layout() const { return layout_; }
  // The symbol for a path, or nullopt (ADS 0x710). Allocates: not for the scan path.
  std::optional<Symbol> find(std::string_view path) const;
  // The data type by name (case-insensitive), or nullptr.
  const DataType* findType(std::string_view name) const;
  // True if any byte of [offset, offset + size) belongs to a read-only variable.
  bool touchesReadOnly(uint32_t offset, uint32_t size) const;

 private:
  std::vector<Symbol> symbols_;
  std::vector<DataType> types_;
  MemoryLayout layout_;
  Resolver resolver_;
  std::unordered_map<std::string, size_t> typeIndex_;  // lower-case name -> types_ index
  std::vector<bool> readOnlyBytes_;
};

// The key of the symbol and type indexes: an asciiLower copy (TwinCAT names are
// case-insensitive). Compare two names in place with iequalsAscii (core/ascii.hpp).
std::string lowerCase(std::string_view s);

}  // namespace virtcom::proto::ads

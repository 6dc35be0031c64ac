#pragma once
// The byte layouts of symbol and data type descriptions (docs/ads.md, Wire reference: Symbol
// services, Symbol entry, Data type entry).
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads {

// One symbol entry (0xF00B item, 0xF009 reply), padded to a multiple of 4 bytes:
// entryLength, IG, IO, size, ADST, u16 flags, u16 arrayDims (0), u16 name/type/comment lengths,
// then name NUL, type NUL, comment NUL.
void appendSymbolEntry(std::vector<uint8_t>& out, const Symbol& s);

// Reads one symbol entry (the 0xF009 reply of a TwinCAT or of this server) back: the fields
// above, with the name and type strings; array info, GUID, attributes and padding that follow
// are skipped (clients step by entryLength). Nullopt if the entry is shorter than its fields or
// its lengths disagree. Allocates the two strings.
std::optional<Symbol> parseSymbolEntry(std::span<const uint8_t> entry);

// One data type entry (0xF00E item, 0xF011 reply) with its array bounds, one DataItem sub-entry
// per member and its enum infos, padded to a multiple of 4 bytes.
void appendDataTypeEntry(std::vector<uint8_t>& out, const DataType& t);

// The extended 0xF003 reply (readLength > 4): handle, size, type decoration (0), u16 type-name
// length, type name NUL.
void appendExtendedHandle(std::vector<uint8_t>& out, uint32_t handle, const Symbol& s);

// 0xF00C (8 bytes) / 0xF00F (24 or 64 bytes) upload info: counts and byte totals of the two uploads.
struct UploadInfo {
  uint32_t symbolCount = 0, symbolLength = 0, dataTypeCount = 0, dataTypeLength = 0;
};
void appendUploadInfo(std::vector<uint8_t>& out, const UploadInfo& info, size_t bytes);

}  // namespace virtcom::proto::ads

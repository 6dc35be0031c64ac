#include "proto/ads/entries.hpp"

#include "proto/ads/byte_io.hpp"

namespace virtcom::proto::ads {

namespace {

void padTo4(LittleEndianWriter& w, size_t entryStart) {
  while ((w.size() - entryStart) % 4 != 0) w.u8(0);
}

// The 42-byte head and the three strings of a data type entry; returns the entry's start.
size_t beginTypeEntry(LittleEndianWriter& w, const std::string& name, const std::string& type, uint32_t size,
                      uint32_t offset, uint32_t adsType, uint32_t flags, size_t dims, size_t subItems) {
  const size_t start = w.size();
  w.u32(0);  // entryLength, patched by endEntry
  w.u32(1);  // version
  w.u32(0);  // hashValue
  w.u32(0);  // typeHashValue
  w.u32(size);
  w.u32(offset);
  w.u32(adsType);
  w.u32(flags);
  w.u16(static_cast<uint16_t>(name.size()));
  w.u16(static_cast<uint16_t>(type.size()));
  w.u16(0);  // comment
  w.u16(static_cast<uint16_t>(dims));
  w.u16(static_cast<uint16_t>(subItems));
  w.cstring(name);
  w.cstring(type);
  w.cstring("");
  return start;
}

void endEntry(LittleEndianWriter& w, size_t start) {
  padTo4(w, start);
  w.put32(start, static_cast<uint32_t>(w.size() - start));
}

}  // namespace

void appendSymbolEntry(std::vector<uint8_t>& out, const Symbol& s) {
  LittleEndianWriter w(out);
  const size_t start = w.size();
  w.u32(0);
  w.u32(s.indexGroup);
  w.u32(s.indexOffset);
  w.u32(s.size);
  w.u32(s.adsType);
  w.u16(s.flags);
  w.u16(0);  // arrayDimension: the type carries the bounds
  w.u16(static_cast<uint16_t>(s.name.size()));
  w.u16(static_cast<uint16_t>(s.type.size()));
  w.u16(0);
  w.cstring(s.name);
  w.cstring(s.type);
  w.cstring("");
  endEntry(w, start);
}

std::optional<Symbol> parseSymbolEntry(std::span<const uint8_t> entry) {
  LittleEndianReader r(entry);
  auto length = r.u32();
  if (!length || *length > entry.size() || *length < 30) return std::nullopt;
  LittleEndianReader in(entry.first(*length));
  in.u32();
  Symbol s;
  s.indexGroup = *in.u32();
  s.indexOffset = *in.u32();
  s.size = *in.u32();
  s.adsType = *in.u32();
  s.flags = *in.u16();
  in.u16();  // arrayDimension count
  const uint16_t nameLength = *in.u16(), typeLength = *in.u16();
  in.u16();  // commentLength
  auto name = in.bytes(nameLength + 1u);
  auto type = in.bytes(typeLength + 1u);
  if (!name || !type) return std::nullopt;
  s.name.assign(name->begin(), name->end() - 1);
  s.type.assign(type->begin(), type->end() - 1);
  return s;
}

void appendDataTypeEntry(std::vector<uint8_t>& out, const DataType& t) {
  LittleEndianWriter w(out);
  const size_t start = beginTypeEntry(w, t.name, t.baseType, t.size, 0, t.adsType, t.flags, t.dims.size(), t.members.size());
  for (const ArrayBounds& d : t.dims) {
    w.u32(static_cast<uint32_t>(d.lowerBound));
    w.u32(d.elementCount);
  }
  for (const DataType::Member& m : t.members) {
    const size_t item = beginTypeEntry(w, m.name, m.type, m.size, m.offset, m.adsType, kTypeFlagDataItem, 0, 0);
    endEntry(w, item);
  }
  if (t.flags & kTypeFlagEnumInfos) {
    w.u16(static_cast<uint16_t>(t.enumerators.size()));
    for (const DataType::Enumerator& e : t.enumerators) {
      w.u8(static_cast<uint8_t>(e.name.size()));
      w.cstring(e.name);
      for (uint32_t i = 0; i < t.size && i < 8; ++i) w.u8(static_cast<uint8_t>(static_cast<uint64_t>(e.value) >> (8 * i)));
    }
  }
  endEntry(w, start);
}

void appendExtendedHandle(std::vector<uint8_t>& out, uint32_t handle, const Symbol& s) {
  LittleEndianWriter w(out);
  w.u32(handle);
  w.u32(s.size);
  w.u32(0);  // type decoration: meaning unknown (spec 11.2), 0 works with every client
  w.u16(static_cast<uint16_t>(s.type.size()));
  w.cstring(s.type);
}

void appendUploadInfo(std::vector<uint8_t>& out, const UploadInfo& info, size_t bytes) {
  LittleEndianWriter w(out);
  const size_t start = w.size();
  w.u32(info.symbolCount);
  w.u32(info.symbolLength);
  if (bytes >= 24) {
    w.u32(info.dataTypeCount);
    w.u32(info.dataTypeLength);
    w.u32(0);  // maxDynamicSymbolCount
    w.u32(0);  // dynamicSymbolCount
  }
  if (bytes >= 64) {
    w.u32(0);      // invalidDynamicSymbolCount
    w.u32(65001);  // encodingCodePage: names are UTF-8 (ST identifiers are ASCII anyway)
    w.u32(2);      // flags: includes base types
    w.zeros(64 - (w.size() - start));
  }
}

}  // namespace virtcom::proto::ads

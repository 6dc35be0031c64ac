// Session: Read / Write / ReadWrite by index group, symbol handles and the by-name symbol
// services (docs/ads.md, Wire reference: Symbol services).
#include <algorithm>
#include <string_view>

#include "proto/ads/byte_io.hpp"
#include "proto/ads/entries.hpp"
#include "proto/ads/index_group.hpp"
#include "proto/ads/session.hpp"

namespace virtcom::proto::ads {

namespace {

// A name as sent: ads-client appends a NUL, AdsLib does not (docs/ads.md, Symbol services).
std::string_view nameOf(std::span<const uint8_t> data) {
  std::string_view s(reinterpret_cast<const char*>(data.data()), data.size());
  return s.substr(0, s.find('\0'));
}

}  // namespace

AdsError Session::read(uint32_t ig, uint32_t io, uint32_t length, std::vector<uint8_t>& reply) {
  if (ig != static_cast<uint32_t>(IndexGroup::SymValueByHandle)) return device_.read(ig, io, length, reply);
  const Symbol* h = findHandle(io);
  if (!h) return AdsError::SymbolNotFound;
  // A longer read (pyads reads every STRING with a 1024-byte buffer) gets the symbol's bytes and
  // its actual length, as TwinCAT answers it (docs/ads.md, Read lengths).
  return device_.read(h->indexGroup, h->indexOffset, std::min(length, h->size), reply);
}

AdsError Session::write(uint32_t ig, uint32_t io, std::span<const uint8_t> data) {
  switch (static_cast<IndexGroup>(ig)) {
    case IndexGroup::SymValueByHandle: {
      const Symbol* h = findHandle(io);
      if (!h) return AdsError::SymbolNotFound;
      if (data.size() > h->size) return AdsError::InvalidSize;
      if (h->flags & kSymbolFlagReadOnly) return AdsError::AccessDenied;
      return device_.write(h->indexGroup, h->indexOffset, data);
    }
    case IndexGroup::SymReleaseHandle: {
      LittleEndianReader in(data);
      auto handle = in.u32();
      if (!handle || in.remaining() != 0) return AdsError::InvalidSize;
      return device_.handles().release(currentClient_, *handle);
    }
    default: return device_.write(ig, io, data);
  }
}

AdsError Session::readWrite(uint32_t ig, uint32_t io, uint32_t readLength, std::span<const uint8_t> data,
                            std::vector<uint8_t>& reply, bool inSum) {
  switch (static_cast<IndexGroup>(ig)) {
    case IndexGroup::SymHandleByName:
    case IndexGroup::SymValueByName:
    case IndexGroup::SymInfoByName:
    case IndexGroup::SymInfoByNameEx:
    case IndexGroup::DataTypeByNameEx: return symbolService(ig, readLength, data, reply);
    case IndexGroup::SumRead:
    case IndexGroup::SumWrite:
    case IndexGroup::SumReadWrite:
    case IndexGroup::SumAddNotification:
    case IndexGroup::SumDeleteNotification: {
      if (inSum) return AdsError::ServiceNotSupported;
      if (io == 0 || io > device_.config().maxSumItems) return AdsError::InvalidData;
      switch (static_cast<IndexGroup>(ig)) {
        case IndexGroup::SumRead: return sumRead(io, readLength, data, reply);
        case IndexGroup::SumWrite: return sumWrite(io, data, reply);
        case IndexGroup::SumReadWrite: return sumReadWrite(io, data, reply);
        case IndexGroup::SumAddNotification: return sumAddNotifications(io, data, reply);
        default: return sumDeleteNotifications(io, data, reply);
      }
    }
    default:
      // A ReadWrite on a plain group is a write (nothing to read back) or a read (nothing written).
      if (readLength == 0) return write(ig, io, data);
      if (data.empty()) return read(ig, io, readLength, reply);
      return isKnownGroup(ig) ? AdsError::ServiceNotSupported : AdsError::InvalidIndexGroup;
  }
}

AdsError Session::symbolService(uint32_t ig, uint32_t readLength, std::span<const uint8_t> nameBytes,
                                std::vector<uint8_t>& reply) {
  const std::string_view name = nameOf(nameBytes);
  const size_t start = reply.size();
  // Never more than the client asked for (AdsLib fails with 0x705 otherwise: docs/ads.md, Commands).
  auto fits = [&] { return readLength == kAnyLength || reply.size() - start <= readLength; };
  if (static_cast<IndexGroup>(ig) == IndexGroup::DataTypeByNameEx) {
    const DataType* t = device_.table().findType(name);
    if (!t) return AdsError::SymbolNotFound;
    appendDataTypeEntry(reply, *t);
    return fits() ? AdsError::None : AdsError::InvalidSize;
  }
  auto symbol = device_.table().find(name);
  if (!symbol) return AdsError::SymbolNotFound;
  switch (static_cast<IndexGroup>(ig)) {
    case IndexGroup::SymHandleByName: {
      // readLength 4: the classic reply (AdsLib, pyads); more: the extended one (ads-client).
      if (readLength < 4) return AdsError::InvalidSize;
      uint32_t handle = 0;
      if (AdsError e = device_.handles().create(currentClient_, *symbol, handle); e != AdsError::None) return e;
      if (readLength == 4) LittleEndianWriter(reply).u32(handle);
      else appendExtendedHandle(reply, handle, *symbol);
      if (fits()) return AdsError::None;
      device_.handles().release(currentClient_, handle);
      return AdsError::InvalidSize;
    }
    case IndexGroup::SymValueByName: {
      if (readLength != kAnyLength && readLength < symbol->size) return AdsError::InvalidSize;
      return device_.read(symbol->indexGroup, symbol->indexOffset, symbol->size, reply);
    }
    case IndexGroup::SymInfoByName: {
      if (readLength < 12) return AdsError::InvalidSize;
      LittleEndianWriter w(reply);
      w.u32(symbol->indexGroup);
      w.u32(symbol->indexOffset);
      w.u32(symbol->size);
      return AdsError::None;
    }
    default:
      appendSymbolEntry(reply, *symbol);
      return fits() ? AdsError::None : AdsError::InvalidSize;
  }
}

}  // namespace virtcom::proto::ads

// Session: sum commands (docs/ads.md, Wire reference: Sum commands). The outer result is 0 once
// the batch parsed; each item carries its own result.
#include "proto/ads/byte_io.hpp"
#include "proto/ads/index_group.hpp"
#include "proto/ads/session.hpp"

namespace virtcom::proto::ads {

AdsError Session::sumRead(uint32_t n, uint32_t readLength, std::span<const uint8_t> data, std::vector<uint8_t>& reply) {
  // Request: n x {IG, IO, length}. Reply: n results, then each item's data at its requested
  // length (a failed item's slot is zero-filled so later slots stay where the client expects).
  if (data.size() != 12ull * n) return AdsError::InvalidSize;
  LittleEndianReader in(data);
  uint64_t total = 4ull * n;
  for (uint32_t i = 0; i < n; ++i) {
    in.u32();
    in.u32();
    total += *in.u32();
  }
  if (readLength != kAnyLength && total > readLength) return AdsError::InvalidSize;
  if (total > device_.config().maxSumReadBytes) return AdsError::InvalidSize;
  const size_t results = reply.size();
  LittleEndianWriter w(reply);
  w.zeros(4ull * n);
  LittleEndianReader items(data);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t ig = *items.u32(), io = *items.u32(), length = *items.u32();
    const size_t slot = reply.size();
    AdsError e = read(ig, io, length, reply);
    if (e != AdsError::None) reply.resize(slot);
    reply.resize(slot + length, 0);
    w.put32(results + 4ull * i, static_cast<uint32_t>(e));
  }
  return AdsError::None;
}

AdsError Session::sumWrite(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply) {
  // Request: n x {IG, IO, length}, then all the data. Reply: n results.
  if (data.size() < 12ull * n) return AdsError::InvalidSize;
  LittleEndianReader items(data.first(12ull * n));
  LittleEndianReader payload(data.subspan(12ull * n));
  LittleEndianWriter w(reply);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t ig = *items.u32(), io = *items.u32(), length = *items.u32();
    auto bytes = payload.bytes(length);
    w.u32(static_cast<uint32_t>(bytes ? write(ig, io, *bytes) : AdsError::InvalidSize));
  }
  return AdsError::None;
}

AdsError Session::sumReadWrite(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply) {
  // Request: n x {IG, IO, readLength, writeLength}, then all write data. Reply: n x {result,
  // returned length}, then each item's data at its returned length.
  if (data.size() < 16ull * n) return AdsError::InvalidSize;
  LittleEndianReader items(data.first(16ull * n));
  LittleEndianReader payload(data.subspan(16ull * n));
  const size_t heads = reply.size();
  LittleEndianWriter w(reply);
  w.zeros(8ull * n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t ig = *items.u32(), io = *items.u32(), readLength = *items.u32(), writeLength = *items.u32();
    auto bytes = payload.bytes(writeLength);
    const size_t slot = reply.size();
    AdsError e = bytes ? readWrite(ig, io, readLength, *bytes, reply, true) : AdsError::InvalidSize;
    if (e != AdsError::None) reply.resize(slot);
    w.put32(heads + 8ull * i, static_cast<uint32_t>(e));
    w.put32(heads + 8ull * i + 4, static_cast<uint32_t>(reply.size() - slot));
  }
  return AdsError::None;
}

AdsError Session::sumAddNotifications(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply) {
  // Request: n x the 40-byte AddDeviceNotification body. Reply: n x {result, handle}.
  if (data.size() != 40ull * n) return AdsError::InvalidSize;
  LittleEndianWriter w(reply);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t handle = 0;
    AdsError e = addNotification(data.subspan(40ull * i, 40), handle);
    w.u32(static_cast<uint32_t>(e));
    w.u32(handle);
  }
  return AdsError::None;
}

AdsError Session::sumDeleteNotifications(uint32_t n, std::span<const uint8_t> data, std::vector<uint8_t>& reply) {
  // Request: n handles. Reply: n results.
  if (data.size() != 4ull * n) return AdsError::InvalidSize;
  LittleEndianReader in(data);
  LittleEndianWriter w(reply);
  for (uint32_t i = 0; i < n; ++i) w.u32(static_cast<uint32_t>(deleteNotification(*in.u32())));
  return AdsError::None;
}

}  // namespace virtcom::proto::ads

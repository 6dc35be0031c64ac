#include "core/write_audit.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <numeric>

#include "core/clock.hpp"

namespace virtcom {

namespace {

std::string hexBytes(std::span<const uint8_t> bytes) {
  std::string out = "16#";
  char two[3];
  for (uint8_t b : bytes) {
    std::snprintf(two, sizeof two, "%02X", b);
    out += two;
  }
  return out;
}

}  // namespace

std::string formatWriteRecord(const WriteRecord& r) {
  return std::string(writeProtocolName(r.writer.protocol)) + " " + writerPeer(r.writer) + " " + writtenVariableText(r) + ": " + r.oldValue + " -> " + r.newValue + (r.writer.force ? " (forced)" : "");
}

std::string formatWriteRecordWithTimes(const WriteRecord& r) {
  char virtualTime[32];
  std::snprintf(virtualTime, sizeof virtualTime, "%.3fs", static_cast<double>(r.virtualNs) * 1e-9);
  return std::string(virtualTime) + " " + utcTimeText(r.wallNs) + " " + formatWriteRecord(r);
}

void AuditedNames::narrow(Place&, uint32_t, uint32_t) const {}

WriteAudit::WriteAudit(std::unique_ptr<AuditedNames> names, Sink sink) : names_(std::move(names)), sink_(std::move(sink)) {}

uint64_t WriteAudit::total() const { return std::accumulate(counts_.begin(), counts_.end(), uint64_t{0}); }

void WriteAudit::beforeEdit(const ExternalWriter& writer, std::span<const uint8_t> target, uint32_t address, uint32_t offset,
                            uint32_t size, uint8_t bitMask) {
  if (offset >= target.size() || size == 0) return;
  size = std::min<uint32_t>(size, static_cast<uint32_t>(target.size() - offset));
  const uint32_t lo = address + offset, hi = lo + size;
  const int bit = bitMask ? std::countr_zero(bitMask) : -1;
  // The named places the edit touches, each wholly inside `target`.
  using Place = AuditedNames::Place;
  const std::vector<Place>& places = names_->places();
  auto touched = [&](const Place& v) {
    if (v.address < address || v.address + v.size > address + target.size()) return false;
    if (v.bit >= 0) return v.address >= lo && v.address < hi && (bitMask == 0 || v.bit == bit);
    return v.address < hi && v.address + v.size > lo;
  };
  // A bit write names the BOOL at that bit when one is declared, not the WORD around it too.
  const bool bitDeclared = bitMask && std::any_of(places.begin(), places.end(), [&](const Place& v) { return v.bit >= 0 && touched(v); });
  auto wanted = [&](const Place& v) { return touched(v) && (!bitDeclared || v.bit >= 0); };
  candidates_.clear();
  for (const Place& v : places) {
    if (!wanted(v)) continue;
    Pending c{writer, v, nullptr, 0, 0};
    if (c.place.bit < 0) names_->narrow(c.place, std::max(lo, v.address), std::min(hi, v.address + v.size));
    candidates_.push_back(std::move(c));
  }
  // Nothing declared there: the bytes themselves, by location.
  if (candidates_.empty()) candidates_.push_back({writer, Place{{}, lo, static_cast<int8_t>(bit), size, 0}, nullptr, 0, 0});
  for (Pending& c : candidates_) c.at = target.data() + (c.place.address - address);
  // Consecutive edits of the same variables by the same writer (the bytes of one register, the
  // bits of one request) are one write: its old value was taken at the first edit.
  auto same = [](const Pending& a, const Pending& b) {
    return a.writer == b.writer && a.place.address == b.place.address && a.place.bit == b.place.bit && a.place.size == b.place.size &&
           a.place.name == b.place.name;
  };
  if (std::equal(pending_.begin() + static_cast<ptrdiff_t>(openFrom_), pending_.end(), candidates_.begin(), candidates_.end(), same)) return;
  closeOpen();
  for (Pending& c : candidates_) {
    c.oldPos = bytes_.size();
    bytes_.insert(bytes_.end(), c.at, c.at + c.place.size);
    pending_.push_back(std::move(c));
  }
}

void WriteAudit::closeOpen() {
  for (size_t i = openFrom_; i < pending_.size(); ++i) {
    Pending& p = pending_[i];
    p.newPos = bytes_.size();
    bytes_.insert(bytes_.end(), p.at, p.at + p.place.size);
  }
  openFrom_ = pending_.size();
}

WriteRecord WriteAudit::toRecord(const Pending& p, int64_t wallNs) {
  WriteRecord r;
  r.virtualNs = virtualNs_;
  r.wallNs = wallNs;
  r.writer = p.writer;
  const AuditedNames::Place& place = p.place;
  auto value = [&](size_t pos) {
    const auto bytes = std::span<const uint8_t>(bytes_).subspan(pos, place.size);
    if (!place.name.empty())
      if (auto text = names_->valueText(place, bytes)) return *text;
    if (place.bit >= 0) return std::string((bytes[0] >> place.bit) & 1 ? "TRUE" : "FALSE");
    return hexBytes(bytes);
  };
  r.location = names_->location(place);
  r.variable = !place.name.empty() ? place.name : !r.location.empty() ? r.location : "address " + std::to_string(place.address);
  r.oldValue = value(p.oldPos);
  r.newValue = value(p.newPos);
  return r;
}

void WriteAudit::endEdits() {
  if (pending_.empty()) return;
  closeOpen();
  const int64_t wallNs = utcNowNs();
  for (const Pending& p : pending_) {
    ++counts_[static_cast<size_t>(p.writer.protocol)];
    if (sink_) sink_(toRecord(p, wallNs));
  }
  pending_.clear();
  bytes_.clear();
  openFrom_ = 0;
}

void WriteAudit::stateChanged(const ExternalWriter& writer, std::string_view from, std::string_view to) {
  ++counts_[static_cast<size_t>(writer.protocol)];
  if (!sink_) return;
  WriteRecord r;
  r.virtualNs = virtualNs_;
  r.wallNs = utcNowNs();
  r.writer = writer;
  r.variable = kPlcStateVariable;
  r.oldValue = from;
  r.newValue = to;
  sink_(r);
}

}  // namespace virtcom

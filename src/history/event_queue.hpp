#pragma once
// What the recorder hands from the scan thread to the writer thread: fixed-size events in a
// preallocated single-producer single-consumer ring. Pushing copies a few words and never blocks
// or allocates; a full ring refuses the push (the recorder counts it as a drop).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace virtcom::history {

enum class EventKind : uint8_t {
  Change,     // index = signal, raw
  Activity,   // index = activity number; the whole record, sent when it begins and when it ends
  Collision,  // index = collision number
  Fault,      // index = fault number; followed by text events holding source then message
  Text,       // kTextChunk bytes of a fault's text
  Cycle,      // index = number of cycles completed; the cycle's window
  Production, // index = the shift in the plan; one shift occurrence's row as it stands (virtcom monitor)
  Write,      // index = write number; an audited external write, followed by text events holding its texts
};

inline constexpr size_t kTextChunk = 32;
// The texts of a Write event, in the order its text events hold them.
enum WriteText : uint8_t { kWritePeer, kWriteNetId, kWriteVariable, kWriteLocation, kWriteOld, kWriteNew, kWriteTextCount };

struct ActivityEvent {
  uint32_t device, label;
  int64_t startNs, endNs;  // endNs -1 while running
  double energyJ;
  int32_t errorCode;
};
struct CollisionEvent {
  uint32_t zone, deviceA, deviceB, activityA, activityB;
};
struct FaultEvent {
  uint32_t sourceBytes, messageBytes;
};
struct CycleEvent {
  int64_t startNs, endNs;
};
struct WriteEvent {
  int64_t wallNs;  // UTC
  uint16_t textBytes[kWriteTextCount];
  uint8_t protocol;  // WriteProtocol
  bool forced;
};
// Local wall times: ns since 1970-01-01 00:00 local (the `production` table of docs/history.md).
struct ProductionEvent {
  int64_t startWallNs, endWallNs, watchedFromWallNs;
  double planNow;
  uint32_t plan, actual;
};

struct Event {
  EventKind kind = EventKind::Change;
  uint32_t index = 0;
  int64_t timeNs = 0;
  union {
    uint64_t raw = 0;
    ActivityEvent activity;
    CollisionEvent collision;
    FaultEvent fault;
    CycleEvent cycle;
    ProductionEvent production;
    WriteEvent write;
    char text[kTextChunk];
  };
};

class EventQueue {
 public:
  // Room for `capacity` events (at least 1), allocated here once.
  explicit EventQueue(size_t capacity) : capacity_(capacity ? capacity : 1), ring_(new Event[capacity_]) {}

  // Producer: calls fill(event, i) for i in [0, n) on n consecutive slots and publishes them
  // together, or returns false (nothing written) if fewer than n slots are free.
  template <class Fill>
  bool tryPush(size_t n, Fill&& fill) {
    const uint64_t head = head_.load(std::memory_order_relaxed);
    if (head + n - tail_.load(std::memory_order_acquire) > capacity_) return false;
    for (size_t i = 0; i < n; ++i) fill(ring_[(head + i) % capacity_], i);
    head_.store(head + n, std::memory_order_release);
    return true;
  }

  // Consumer: the number of published events not yet consumed, each read with at(i), then
  // released with pop(n).
  size_t available() const { return static_cast<size_t>(head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_relaxed)); }
  const Event& at(size_t i) const { return ring_[(tail_.load(std::memory_order_relaxed) + i) % capacity_]; }
  void pop(size_t n) { tail_.store(tail_.load(std::memory_order_relaxed) + n, std::memory_order_release); }
  size_t capacity() const { return capacity_; }

 private:
  const size_t capacity_;
  std::unique_ptr<Event[]> ring_;
  alignas(64) std::atomic<uint64_t> head_{0};  // written by the producer only
  alignas(64) std::atomic<uint64_t> tail_{0};  // written by the consumer only
};

}  // namespace virtcom::history

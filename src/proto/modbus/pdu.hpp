#pragma once
// Modbus request PDUs answered against byte areas laid out in one of two ways.
// Layout::OpenPlc, a PLC process image with the OpenPLC mapping:
//   coils            0..          -> %QX  (coil 8b+k = bit k of Q byte b)
//   discrete inputs  0..          -> %IX  (read only)
//   input registers  0..          -> %IW  (register n = I bytes 2n..2n+1, read only)
//   holding registers 0..1023     -> %QW  (register n = Q bytes 2n..2n+1)
//   holding registers 1024..2047  -> %MW  (register 1024+n = M bytes 2n..2n+1)
//   holding registers 2048..4095  -> %MD  (registers 2048+2n, +1 = %MDn high word, low word)
//   holding registers 4096..8191  -> %ML  (registers 4096+4n..+3 = %MLn, highest word first)
//   holding registers 8192..      -> %IW  (register 8192+n = I bytes 2n..2n+1) only with
//                                    writableInputs (exec --modbus-writable-inputs)
// Layout::Tables, four independent tables (a served cell's signal map):
//   coils = bits of `outputs`, discrete inputs = bits of `inputs`, holding registers = words
//   of `memory`, input registers = words of `registers`; coils and holding registers whose bit
//   is set in `readOnlyCoils` / `readOnlyHolding` refuse writes (exception 02).
// Areas are little endian (register n = bytes 2n, 2n+1); registers go big endian on the wire.
// Pure functions over spans: no sockets, no threads, no allocation.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/external_write.hpp"

namespace virtcom::proto::modbus {

// MODBUS Application Protocol V1.1b3 section 4.1: a PDU is at most 253 bytes.
inline constexpr size_t kMaxPduSize = 253;
// OpenPLC's holding register ranges for the %M area (its modbus server: MIN_16B/32B/64B_RANGE).
inline constexpr uint16_t kMemoryRegisterBase = 1024;  // %MW0
inline constexpr uint16_t kDoubleRegisterBase = 2048;  // %MD0
inline constexpr uint16_t kLongRegisterBase = 4096;    // %ML0
inline constexpr uint32_t kLongRegisterEnd = 8192;     // one past %ML1023's last register
inline constexpr uint32_t kInputHoldingBase = 8192;    // %IW0 as a holding register (writableInputs)

enum class FunctionCode : uint8_t {
#define MODBUS_FUNCTION(name, code, handler, writes, text) name = code,
#include "proto/modbus/function_codes.def"
#undef MODBUS_FUNCTION
};
// The spec's name of a function code, or nullptr if the server does not implement it.
const char* functionName(uint8_t code);

// Exception codes: MODBUS Application Protocol V1.1b3 section 7.
enum class ExceptionCode : uint8_t {
  IllegalFunction = 0x01,
  IllegalDataAddress = 0x02,
  IllegalDataValue = 0x03,
  ServerDeviceFailure = 0x04,
  ServerDeviceBusy = 0x06,  // the write queue is full until the next scan drains it
};

enum class Area : uint8_t { Inputs, Outputs, Memory, Registers };
enum class Layout : uint8_t { OpenPlc, Tables };

// The areas a request reads and writes (%I, %Q, %M of a PLC; see the layouts above).
struct ImageView {
  std::span<uint8_t> inputs, outputs, memory;
  std::span<uint8_t> registers = {};  // Layout::Tables: the input registers
  Layout layout = Layout::OpenPlc;
  std::span<const uint8_t> readOnlyCoils = {}, readOnlyHolding = {};  // Layout::Tables: bit per coil/register
  bool writableInputs = false;  // Layout::OpenPlc: %IW also as holding registers from kInputHoldingBase
  bool readOnly = false;        // every writing function refused with exception 01 (--modbus-readonly)
  // Where each area (by Area) lies in the PLC's data area: the write audit names the variables
  // written by it (Layout::OpenPlc; the input image stands for the %I area).
  std::array<uint32_t, 4> plcAddresses{};
  std::span<uint8_t> bytes(Area a) const {
    switch (a) {
      case Area::Inputs: return inputs;
      case Area::Outputs: return outputs;
      case Area::Memory: return memory;
      case Area::Registers: return registers;
    }
    return {};
  }
};

// One byte of a write: bits in `mask` take their value from `value`.
struct ByteEdit {
  Area area = Area::Outputs;
  uint32_t offset = 0;
  uint8_t value = 0;
  uint8_t mask = 0;
};
// Applies the edit if it lies inside the view (edits are made against views of the same sizes).
void applyEdit(const ByteEdit& e, const ImageView& image);

// A bounded list of byte edits, each with the client that made it (setWriter, before a request
// is answered). Allocates only in the constructor: push never allocates, so it can be filled and
// drained on the scan path.
class EditQueue {
 public:
  explicit EditQueue(size_t capacity) {
    edits_.reserve(capacity);
    writers_.reserve(capacity);
  }
  bool hasRoom(size_t n) const { return edits_.capacity() - edits_.size() >= n; }
  void setWriter(const ExternalWriter& w) { writer_ = w; }
  // Precondition: hasRoom(1).
  void push(const ByteEdit& e) {
    edits_.push_back(e);
    writers_.push_back(writer_);
  }
  std::span<const ByteEdit> edits() const { return edits_; }
  // Applies every edit to `image` in arrival order, each reported to `audit` first (if given).
  void applyTo(const ImageView& image, WriteObserver* audit) const;
  void clear() {
    edits_.clear();
    writers_.clear();
  }

 private:
  std::vector<ByteEdit> edits_;
  std::vector<ExternalWriter> writers_;
  ExternalWriter writer_{WriteProtocol::Modbus};
};

// Answers one request PDU (function code + data). Reads come from `image`; a write is checked
// whole first, then applied to `image` and appended to `edits` (all or nothing; exception 06 if
// `edits` has no room). Malformed or out-of-range requests get an exception response
// (function | 0x80, code). Returns the response length written to `response`; never fails.
size_t handlePdu(std::span<const uint8_t> request, const ImageView& image, EditQueue& edits,
                 std::span<uint8_t, kMaxPduSize> response);

}  // namespace virtcom::proto::modbus

// libFuzzer target for the Modbus TCP codec: the input is a receive stream, cut into frames by
// scanFrame exactly as the server does, each answered against a small process image (OpenPLC
// layout, with %MD/%ML) and against a served cell's four tables with read-only entries.
// Finds out-of-bounds reads/writes and aborts in the MBAP and PDU parsers.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "proto/modbus/mbap.hpp"

namespace mb = virtcom::proto::modbus;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static std::array<uint8_t, 64> inputs{}, outputs{}, memory{}, registers{};
  static const std::array<uint8_t, 8> readOnlyCoils{0x0f, 0, 0xf0}, readOnlyHolding{0x03, 0, 0, 0x80};
  static mb::EditQueue edits(512);
  mb::ImageView openPlc{inputs, outputs, memory};
  mb::ImageView tables{inputs, outputs, memory, registers, mb::Layout::Tables, readOnlyCoils, readOnlyHolding};
  std::span<const uint8_t> stream(data, size);
  std::array<uint8_t, mb::kMaxAduSize> response{};
  while (true) {
    mb::FrameScan scan = mb::scanFrame(stream);
    if (scan.status != mb::FrameStatus::Complete) break;
    for (const mb::ImageView& image : {openPlc, tables}) {
      size_t n = mb::handleFrame(stream.first(scan.size), image, edits, response);
      if (n < mb::kMbapHeaderSize + 2 || n > response.size()) __builtin_trap();
    }
    if (!edits.hasRoom(256)) edits.clear();
    stream = stream.subspan(scan.size);
  }
  return 0;
}

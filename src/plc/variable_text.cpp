#include "plc/variable_text.hpp"

#include <algorithm>
#include <cstring>

namespace virtcom::plc {

std::string writeVariableText(const bc::Module& m, const bc::VarRef& ref, std::string_view text, uint8_t* memory,
                              uint8_t* inputImage) {
  std::string problem = bc::writeValueFromText(m, ref, text, memory);
  if (problem.empty() && inputImage) syncInputImage(m, ref, memory, inputImage);
  return problem;
}

void syncInputImage(const bc::Module& m, const bc::VarRef& ref, const uint8_t* memory, uint8_t* inputImage) {
  const bc::ProcessArea& in = m.inputs;
  if (ref.address < in.address || ref.address >= in.address + in.size) return;
  uint32_t size = std::max<uint32_t>(m.types[ref.type].size, 1);
  std::memcpy(inputImage + (ref.address - in.address), memory + ref.address, std::min(size, in.address + in.size - ref.address));
}

}  // namespace virtcom::plc

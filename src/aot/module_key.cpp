#include "aot/module_key.hpp"

#include <cstdio>
#include <cstring>
#include <string_view>

#include "core/build_id.hpp"
#include "core/content_hash.hpp"
#include "vm/compiled.hpp"

namespace virtcom::aot {

namespace {

template <typename T>
void append(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

std::string moduleKey(const bc::Module& m, uint32_t unitInstructions) {
  const std::string& buildId = binaryBuildId();
  if (buildId.empty()) return {};
  std::string bytes = buildId;
  append(bytes, vm::kAotAbiVersion);
  append(bytes, unitInstructions);
  append(bytes, m.staticSize);
  append(bytes, m.memorySize());
  for (const bc::Instr& ins : m.code) {
    append(bytes, ins.op);
    append(bytes, ins.a);
    append(bytes, ins.bx());
  }
  bytes.append(reinterpret_cast<const char*>(m.constants.data()), m.constants.size() * sizeof(uint64_t));
  for (const bc::IndexDesc& index : m.indexes) {
    append(bytes, index.lo);
    append(bytes, index.count);
    append(bytes, index.stride);
  }
  for (const bc::PouInfo& pou : m.pous) {
    bytes += pou.name;
    bytes += '\0';
    append(bytes, pou.codeStart);
    append(bytes, pou.codeSize);
    append(bytes, pou.numRegs);
  }
  return hashHex(bytes);
}

}  // namespace virtcom::aot

// libFuzzer target for the module file (bytecode/module_file.*: the compile cache's files, read
// from a folder of the user's): the input is a file without its checksum, which the target adds,
// so mutations reach the member readers instead of stopping at the checksum. Any bytes must give
// an error text or a module; a module the verifier accepts must write back to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bytecode/module_file.hpp"
#include "bytecode/verifier.hpp"
#include "core/content_hash.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const uint64_t checksum = virtcom::hashText(bytes);
  bytes.append(reinterpret_cast<const char*>(&checksum), sizeof checksum);
  virtcom::bc::Module m;
  if (!virtcom::bc::decodeModule(bytes, m).empty()) return 0;
  if (!virtcom::bc::verifyModule(m).empty()) return 0;
  if (virtcom::bc::encodeModule(m) != bytes) std::abort();
  return 0;
}

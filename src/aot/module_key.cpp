#include "aot/module_key.hpp"

#include <link.h>

#include <cstdio>
#include <cstring>
#include <string_view>

#include "aot/c_source.hpp"
#include "vm/compiled.hpp"

namespace virtcom::aot {

namespace {

// The GNU build id (hex) of the loaded object whose segments hold `address`, from its PT_NOTE
// segments in memory (no file is read).
struct BuildIdSearch {
  uintptr_t address;
  std::string id;
};

std::string buildIdOfNotes(const char* notes, size_t size) {
  size_t at = 0;
  while (at + sizeof(ElfW(Nhdr)) <= size) {
    ElfW(Nhdr) header;
    std::memcpy(&header, notes + at, sizeof header);
    const size_t name = at + sizeof header, desc = name + ((header.n_namesz + 3) & ~size_t{3});
    const size_t next = desc + ((header.n_descsz + 3) & ~size_t{3});
    if (next > size) break;
    if (header.n_type == NT_GNU_BUILD_ID && header.n_namesz == 4 && std::memcmp(notes + name, "GNU", 4) == 0) {
      std::string hex;
      char byte[3];
      for (size_t i = 0; i < header.n_descsz; ++i) {
        std::snprintf(byte, sizeof byte, "%02x", static_cast<unsigned char>(notes[desc + i]));
        hex += byte;
      }
      return hex;
    }
    at = next;
  }
  return {};
}

int searchObject(dl_phdr_info* info, size_t, void* data) {
  auto* search = static_cast<BuildIdSearch*>(data);
  bool holds = false;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& segment = info->dlpi_phdr[i];
    const uintptr_t start = info->dlpi_addr + segment.p_vaddr;
    if (segment.p_type == PT_LOAD && search->address >= start && search->address < start + segment.p_memsz) holds = true;
  }
  if (!holds) return 0;
  for (int i = 0; i < info->dlpi_phnum && search->id.empty(); ++i) {
    const ElfW(Phdr)& segment = info->dlpi_phdr[i];
    if (segment.p_type == PT_NOTE)
      search->id = buildIdOfNotes(reinterpret_cast<const char*>(info->dlpi_addr + segment.p_vaddr), segment.p_memsz);
  }
  return 1;
}

const std::string& generatorBuildId() {
  static const std::string id = [] {
    BuildIdSearch search{reinterpret_cast<uintptr_t>(&moduleKey), {}};
    dl_iterate_phdr(searchObject, &search);
    return search.id;
  }();
  return id;
}

template <typename T>
void append(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

std::string moduleKey(const bc::Module& m, uint32_t unitInstructions) {
  const std::string& buildId = generatorBuildId();
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
  char key[17];
  std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(hashText(bytes)));
  return key;
}

}  // namespace virtcom::aot

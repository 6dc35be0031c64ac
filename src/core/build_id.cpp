#include "core/build_id.hpp"

#include <link.h>

#include <cstdio>
#include <cstring>

namespace virtcom {

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

}  // namespace

const std::string& binaryBuildId() {
  static const std::string id = [] {
    BuildIdSearch search{reinterpret_cast<uintptr_t>(&binaryBuildId), {}};
    dl_iterate_phdr(searchObject, &search);
    return search.id;
  }();
  return id;
}

}  // namespace virtcom

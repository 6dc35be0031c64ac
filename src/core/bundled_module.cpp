#include "core/bundled_module.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

namespace virtcom {

TextResult<void*> bundledModuleSymbol(const std::string& file, const char* symbol) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return TextResult<void*>::failure("cannot find the virtcom executable to load " + file + ": " + ec.message());
  const std::string path = (exe.parent_path() / file).string();
  // RTLD_LOCAL: the module's libraries stay out of the global scope the rest of the process resolves in.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    // dlerror() names the path it tried.
    return TextResult<void*>::failure("cannot load the module " + file + " (built and installed beside the virtcom executable): " +
                                      (why ? why : path + ": unknown reason"));
  }
  void* address = ::dlsym(handle, symbol);
  if (!address) return TextResult<void*>::failure(path + " has no function " + symbol + ": not the module this virtcom was built with");
  return address;
}

}  // namespace virtcom

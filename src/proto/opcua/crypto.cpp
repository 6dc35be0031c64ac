#include "proto/opcua/crypto.hpp"

#include <stdexcept>

#include "core/bundled_module.hpp"

// Defined only where crypto_module.cpp is linked into the binary (tests, fuzz targets): weak, so
// the executable, which does not link it, sees a null address and loads the module instead.
extern "C" [[gnu::weak]] const virtcom::proto::opcua::CryptoCalls* virtcomCryptoCalls();

namespace virtcom::proto::opcua {

TextResult<const CryptoCalls*> loadCrypto() {
  static const TextResult<const CryptoCalls*> loaded = []() -> TextResult<const CryptoCalls*> {
    if (virtcomCryptoCalls) return virtcomCryptoCalls();
    auto symbol = bundledModuleSymbol(kCryptoModule, kCryptoCallsSymbol);
    if (!symbol) return TextResult<const CryptoCalls*>::failure(symbol.error());
    return reinterpret_cast<GetCryptoCalls>(*symbol)();
  }();
  return loaded;
}

const CryptoCalls& crypto() {
  auto calls = loadCrypto();
  if (!calls) throw std::runtime_error(calls.error());
  return **calls;
}

std::string lowerHex(std::span<const uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s;
  for (uint8_t b : bytes) {
    s += kDigits[b >> 4];
    s += kDigits[b & 15];
  }
  return s;
}

}  // namespace virtcom::proto::opcua

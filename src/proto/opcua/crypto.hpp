#pragma once
// Where the OPC UA stack gets its cryptography: the module virtcom-crypto.so beside the
// executable (crypto_module.hpp says why it is a module), or its code linked into the binary
// itself (unit tests and fuzz targets link crypto_module.cpp and need no module file).
#include <cstdint>
#include <span>
#include <string>

#include "core/text_result.hpp"
#include "proto/opcua/crypto_module.hpp"

namespace virtcom::proto::opcua {

// The calls, loading the module on the first call; failure: the module is missing or is not the
// one this virtcom was built with (the message names the file). Thread-safe.
TextResult<const CryptoCalls*> loadCrypto();

// The calls of an earlier successful loadCrypto() (or loaded now); throws std::runtime_error with
// loadCrypto()'s message when there is none, for code that has no way to report it otherwise.
const CryptoCalls& crypto();

// The bytes as lower-case hexadecimal, two digits each (salts, hashes, certificate thumbprints).
std::string lowerHex(std::span<const uint8_t> bytes);

}  // namespace virtcom::proto::opcua

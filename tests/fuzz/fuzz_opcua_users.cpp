// libFuzzer target for the OPC UA users file (`--opcua-users FILE`, docs/opcua.md, Users and
// roles): parseUserAccounts on any bytes. A refusal names the file, line and column; every
// account accepted writes back (formatUserAccount) to a line that reads as the same account, and
// is found by its name. Passwords are not hashed here (PBKDF2 at 10,000 iterations or more per
// input would leave the parser few executions).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "proto/opcua/user_accounts.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace opcua = virtcom::proto::opcua;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto accounts = opcua::parseUserAccounts(text, "users.txt");
  if (!accounts) {
    if (!accounts.error().starts_with("users.txt:")) __builtin_trap();  // an error says where
    return 0;
  }
  for (const opcua::UserAccount& a : *accounts) {
    if (opcua::findUserAccount(*accounts, a.name) != &a) __builtin_trap();  // names are unique
    const auto again = opcua::parseUserAccounts(opcua::formatUserAccount(a), "users.txt");
    if (!again || again->size() != 1) __builtin_trap();
    const opcua::UserAccount& b = again->front();
    if (b.name != a.name || b.access != a.access || b.iterations != a.iterations || b.salt != a.salt || b.hash != a.hash)
      __builtin_trap();
  }
  return 0;
}

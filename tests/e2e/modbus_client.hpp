#pragma once
// libmodbus client connections for the Modbus e2e tests (modbus_e2e_tests).
#include <modbus.h>

namespace virtcom::e2e {

// A libmodbus TCP connection to 127.0.0.1:port with a 5 s response timeout (so a server bug
// fails a test, never hangs it); null if it cannot connect. Free with modbus_close/modbus_free.
inline modbus_t* connectModbus(int port) {
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  if (!ctx) return nullptr;
  modbus_set_response_timeout(ctx, 5, 0);
  if (modbus_connect(ctx) == 0) return ctx;
  modbus_free(ctx);
  return nullptr;
}

}  // namespace virtcom::e2e

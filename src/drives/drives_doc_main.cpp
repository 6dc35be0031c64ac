// virtcom_drives_doc: prints docs/drives.md, generated from the telegram tables.
#include <iostream>

#include "drives/telegram_doc.hpp"

int main() {
  std::cout << virtcom::drives::renderTelegramDoc();
  return 0;
}

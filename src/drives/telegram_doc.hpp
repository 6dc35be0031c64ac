#pragma once
// docs/drives.md, rendered from the telegram tables so the reference cannot drift from the
// codec. The committed file is checked against this output by a unit test.
#include <string>

namespace virtcom::drives {

std::string renderTelegramDoc();

}  // namespace virtcom::drives

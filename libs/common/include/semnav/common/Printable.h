/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <string>

namespace semnav
{
/** `text` as it may be echoed in a one-line message: every byte that does
 * not print (control characters, newlines included, DEL, C1 controls, bytes
 * that are no valid UTF-8) becomes `\xNN`; valid UTF-8 text (accented file
 * names) stays as it is. Idempotent. Use it wherever input is echoed. */
std::string printable(const std::string& text);

}  // namespace semnav

// SHA-256 (FIPS 180-4), for the web page's Content-Security-Policy: the page names the
// digest of its inline script and style, which kinema writes (part of the script is
// generated when the page is written, so the digest is taken then).
#pragma once

#include <string>

namespace kinema {

/// The SHA-256 digest of the bytes, as 64 lowercase hex digits.
std::string sha256_hex(const std::string& bytes);

}  // namespace kinema

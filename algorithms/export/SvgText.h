#pragma once
// The text both SVG documents are made of (SvgWriter.h, IllustrationSvg.h):
// numbers with three decimals and escaped XML text.
#include <array>
#include <charconv>
#include <string>

namespace contour {

inline void appendSvgNumber(std::string& out, double x) {
    std::array<char, 64> buffer{};
    const auto result =
        std::to_chars(buffer.data(), buffer.data() + buffer.size(), x, std::chars_format::fixed, 3);
    out.append(buffer.data(), result.ptr);
}

inline std::string escapeXml(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

} // namespace contour

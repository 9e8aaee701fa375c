// Numbers and lines as a person reads them (issue 31): the colour keys of heat maps and of the probe figure
// (vis/ColorKey.h), the probe figure's key numbers and the viewer's status line share these so that a light size
// reads 1.17 rather than 1.171875, five ticks over a narrow range never print the same label twice, and a status
// line longer than the window wraps instead of running off it. In vis, the lowest area that draws numbers.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace sl
{

// `value` rounded to `significant` digits (at least 1) with trailing zeros dropped: 1.171875 -> "1.17", 2 -> "2",
// 0.000123456 -> "0.000123", 1234.5 -> "1234" (whole numbers up to 10^6 in full rather than "1.23e+03"),
// 2.5e-7 -> "2.5e-07"; "-0" prints as "0"; NaN and infinities as "n/a", "inf", "-inf".
std::string readableNumber(double value, int significant = 3);

// Labels for tick values (any order), with the fewest significant digits from `minSignificant` up to 15 at which
// every two different values get different labels: ticks at 3.4752, 3.4731, 3.4710 over a narrow range read
// "3.475", "3.473", "3.471" where three digits would print "3.48", "3.47", "3.47".
std::vector<std::string> distinctTickLabels(const std::vector<double>& values, int minSignificant = 3);

// `text` in lines of at most `maxChars` characters (at least 16), broken at the last space that leaves a line at
// least half full, else inside a word; continuation lines start with two spaces. Every character of `text` but the
// spaces it breaks at is kept, in order.
std::vector<std::string> wrapAtSpaces(const std::string& text, std::size_t maxChars);

} // namespace sl

// Values as users write them: a number with an optional unit ("0.84mm", "840 um",
// "8.4e-1mm", "250mm/min", "1.57rad"), lists and sizes with units ("0,90deg", "36 x 36 mm",
// "36mmx36mm"), paper names for page sizes ("A4", "letter landscape") and choices in any case
// ("FDM"). Everything is converted to the unit a parameter table declares (slicer/params.h);
// the CLI, job files and any other front end read values through here.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace strand::slicer {

// What a value measures, from its table unit: "mm" a length, "mm/min" a speed, "deg" an
// angle, "px" pixels; "" (counts, factors) takes no unit.
enum class Dimension { None, Length, Speed, Angle, Pixels };

// The dimension of a table unit ("mm/s" is a speed too); nullopt for a unit this file does
// not know (such values take no unit either).
std::optional<Dimension> dimension_of(std::string_view table_unit);

// "a length (mm, cm, m, um, in)", "a plain number (no unit)": what a value of this table
// unit may be written in, for messages.
std::string expected_units(std::string_view table_unit);

// The outcome of reading user text: the numbers in the table's unit, or why not.
struct UnitValues {
  std::vector<double> values;
  // Not numbers at all ("abc", "36x", "1e999"): the caller names the shape it expected.
  bool malformed = false;
  // A unit that does not fit, for the message after "table.key = text: ":
  // "expected a length (mm, cm, m, um, in)" (another dimension or an unknown unit),
  // "expected a plain number (no unit)" (a unit on a count or factor).
  std::string unit_problem;
  bool ok() const { return !malformed && unit_problem.empty(); }
};

// One number with an optional unit, spaces allowed around and between ("0.84", "0.84mm",
// " 840 um ", "8.4e-1mm", "1in", "90 deg", "1.5708rad"). Decimal units convert exactly: the
// result is the double nearest the exact product (840um is the same double as 0.84);
// rad -> deg is within one ulp. Hexadecimal, "inf" and "nan" are not numbers.
UnitValues parse_quantity(std::string_view text, std::string_view table_unit);

// Numbers separated by `separator` (',' for lists; 'x' for sizes, which also accepts 'X' and
// '×'), each with its own unit or one unit after the last that applies to every number
// before it without one: "0,90deg", "36x36mm", "36 x 36", "36mm x 1in". A unit after an
// earlier number but none after the last is refused (ambiguous: "36cm x 36").
UnitValues parse_quantities(std::string_view text, std::string_view table_unit, char separator);

// A paper size (width, height) in mm: "A0".."A6", "letter", "legal", "tabloid", any case,
// portrait unless followed by "landscape" (after a space, '-' or '_': "A4 landscape",
// "a4-landscape"); "portrait" may be written too. nullopt for any other text.
std::optional<std::array<double, 2>> paper_size_mm(std::string_view text);

// "A0, A1, A2, A3, A4, A5, A6, letter, legal, tabloid" for messages and help.
std::string paper_names();

// True when `text` starts like a word rather than a number (a paper name, not a size).
bool looks_like_name(std::string_view text);

// The table's spelling of `text` among `choices`, compared without case ("FDM" -> "fdm");
// nullopt if it is none of them.
std::optional<std::string> match_choice(std::string_view text,
                                        const std::vector<std::string>& choices);

}  // namespace strand::slicer

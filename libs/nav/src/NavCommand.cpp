/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/common/Printable.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavigationErrors.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace semnav
{
namespace
{
/** A number token: false when `s` is no number; throws NavCommandError for
 * a number out of range (1e400) or not finite (nan, inf). */
bool parseNumber(const std::string& s, double& v)
{
	if (s.empty()) return false;
	char* end = nullptr;
	errno = 0;
	v = std::strtod(s.c_str(), &end);
	if (end != s.c_str() + s.size()) return false;
	if (!std::isfinite(v))
		throw NavCommandError(
		    "coordinate " + printable(s) +
		    (errno == ERANGE ? " is out of range" : " is not a finite number"));
	return true;
}

bool parseId(const std::string& s, int& id)
{
	std::string t = (!s.empty() && s[0] == '#') ? s.substr(1) : s;
	if (t.empty() || !std::all_of(t.begin(), t.end(), ::isdigit)) return false;
	if (t.size() > 9) return false;
	id = std::stoi(t);
	return id > 0;
}

[[noreturn]] void badCommand(const std::string& text)
{
	throw NavCommandError(
	    "cannot understand the command '" + printable(text) +
	    "'; expected \"go to the nearest <label>\", \"go to <label> <id>\" "
	    "or \"go to <x> <y>\"");
}
}  // namespace

NavCommand NavCommand::nearest(Label l)
{
	NavCommand c;
	c.kind = Kind::NearestLabel;
	c.label = l;
	return c;
}

NavCommand NavCommand::object(Label l, int id)
{
	NavCommand c;
	c.kind = Kind::Object;
	c.label = l;
	c.objectId = id;
	return c;
}

NavCommand NavCommand::point(double x, double y)
{
	NavCommand c;
	c.kind = Kind::Point;
	c.x = x;
	c.y = y;
	return c;
}

NavCommand NavCommand::parse(const std::string& text)
{
	std::string lower = text;
	std::transform(
	    lower.begin(), lower.end(), lower.begin(),
	    [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
	std::replace(lower.begin(), lower.end(), ',', ' ');
	std::istringstream is(lower);
	std::vector<std::string> w;
	for (std::string t; is >> t;) w.push_back(t);

	if (w.size() < 3 || w[0] != "go" || w[1] != "to") badCommand(text);
	std::size_t i = 2;
	if (w[i] == "the" && i + 1 < w.size() && w[i + 1] == "nearest")
		i += 2;
	else if (w[i] == "nearest")
		i += 1;
	else
		i = 0;
	if (i != 0)
	{
		if (w.size() != i + 1) badCommand(text);
		return nearest(labelFromName(w[i]));
	}
	double x = 0, y = 0;
	if (w.size() == 4 && parseNumber(w[2], x) && parseNumber(w[3], y))
		return point(x, y);
	int id = 0;
	if (w.size() == 4 && parseId(w[3], id))
		return object(labelFromName(w[2]), id);
	if (w.size() == 3 || w.size() == 4)
	{
		// A single unknown word is reported as a label.
		if (!parseNumber(w[2], x)) labelFromName(w[2]);
	}
	badCommand(text);
}

std::string NavCommand::text() const
{
	switch (kind)
	{
		case Kind::NearestLabel:
			return "go to the nearest " + labelName(label);
		case Kind::Object:
			return "go to " + labelName(label) + " " + std::to_string(objectId);
		default:
		{
			char buf[80];
			std::snprintf(buf, sizeof(buf), "go to %.3f %.3f", x, y);
			return buf;
		}
	}
}

}  // namespace semnav

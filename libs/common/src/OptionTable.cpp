/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace semnav
{
namespace
{
std::string formatted(double v, int digits)
{
	char buf[64];
	std::snprintf(buf, sizeof(buf), "%.*g", digits, v);
	return buf;
}
}  // namespace

std::string numberText(double v)
{
	for (int digits : {12, 15})
	{
		const std::string t = formatted(v, digits);
		if (std::strtod(t.c_str(), nullptr) == v) return t;
	}
	return formatted(v, 17);
}

std::string angleText(double deg)
{
	return formatted(deg, 12);
}

int readChoice(
    const mrpt::config::CConfigFileBase& c, const std::string& s,
    const std::string& key, int current, const std::vector<std::string>& names)
{
	std::string t = c.read_string(s, key, "", false);
	const auto b = t.find_first_not_of(" \t\r\n");
	const auto e = t.find_last_not_of(" \t\r\n");
	t = b == std::string::npos ? std::string() : t.substr(b, e - b + 1);
	std::transform(
	    t.begin(), t.end(), t.begin(),
	    [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
	if (t.empty()) return current;
	for (std::size_t i = 0; i < names.size(); i++)
		if (t == names[i]) return static_cast<int>(i);
	std::string list;
	for (const auto& n : names) list += (list.empty() ? "" : " | ") + n;
	throw ConfigError(
	    "[" + s + "] " + key + " = '" + t + "' is not one of " + list);
}

std::vector<double> readCheckedList(
    const mrpt::config::CConfigFileBase& c, const std::string& s,
    const std::string& key, const std::vector<double>& current, double lo,
    double hi)
{
	const std::string text = c.read_string(s, key, "");
	if (text.empty()) return current;
	std::istringstream is(text);
	std::vector<double> out;
	for (std::string t; is >> t;)
	{
		std::size_t n = 0;
		double v = 0;
		try
		{
			v = std::stod(t, &n);
		}
		catch (const std::exception&)
		{
			n = 0;
		}
		if (n != t.size() || !(v >= lo && v <= hi))
			throw ConfigError(
			    "[" + s + "] " + key + ": '" + t + "' is not a number in [" +
			    std::to_string(lo) + ", " + std::to_string(hi) + "]");
		out.push_back(v);
	}
	if (out.empty())
		throw ConfigError("[" + s + "] " + key + ": expected numbers");
	return out;
}

std::string listText(const std::vector<double>& v)
{
	std::string out;
	for (double x : v) out += (out.empty() ? "" : " ") + numberText(x);
	return out;
}

}  // namespace semnav

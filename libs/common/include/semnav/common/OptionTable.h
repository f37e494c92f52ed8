/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>

#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace semnav
{
/** Formats a number as the shortest text that reads back to the same
 * double ("0.05", not "0.050000"). */
std::string numberText(double v);

/** Formats an angle in degrees with 12 significant digits ("20", not
 * "19.999999999999996"). */
std::string angleText(double deg);

/** Reads one word of `names` (trimmed, lower case) from [section] key;
 * returns its index, or `current` when the key is absent. Throws
 * ConfigError "[section] key = 'x' is not one of a | b" otherwise. */
int readChoice(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, int current, const std::vector<std::string>& names);

/** Reads a list of numbers separated by spaces, each in [lo, hi]; keeps
 * `current` when the key is absent. Throws ConfigError naming section, key
 * and the bad number, or when the list is empty. */
std::vector<double> readCheckedList(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, const std::vector<double>& current, double lo,
    double hi);

/** A list of numbers as readCheckedList() reads it back. */
std::string listText(const std::vector<double>& v);

/** The keys of an options struct `T`, each declared once: INI key, member,
 * range, one-line doc. load() and save() are derived from the declaration,
 * with the checks of ConfigChecks.h (unknown keys, numbers, ranges, bools).
 *
 * \code
 * const OptionTable<TOptions>& table() {
 *   static const auto t = OptionTable<TOptions>()
 *     .real("lethal_cost", &TOptions::lethalCost, 1, 1e9, "Blocked cell.")
 *     .real("floor_cost", &TOptions::floorCost, 0, &TOptions::lethalCost,
 *           "Floor.")
 *     .angle("max_angle_deg", &TOptions::maxAngle, 0, 90, "Stored in rad.")
 *     .choice("robot_type", &TOptions::robotType,
 *             {{RobotType::Wheeled, "wheeled"}, {RobotType::Walking,
 *              "walking"}}, "Stairs are passable for walking robots.");
 *   return t;
 * }
 * void TOptions::loadFromConfigFile(const CConfigFileBase& c,
 *     const std::string& s) { table().load(*this, c, s); }
 * \endcode
 *
 * Keys are read in declaration order; a range bound may be a number, a
 * member of `T` or any function of `T` (evaluated on the values read so
 * far). check() entries run in place, in order. Loading is all or nothing:
 * on any error `T` is left unchanged. Units are the key's suffix (_m, _deg,
 * _px, _s) and the doc's. */
template <class T>
class OptionTable
{
public:
	/** A range bound: a number, a member pointer or a function of T. */
	class Bound
	{
	public:
		Bound(double v) : m_f([v](const T&) { return v; }) {}
		template <
		    class F, class = std::enable_if_t<
		                 std::is_invocable_r_v<double, F, const T&>>>
		Bound(F f) : m_f([f](const T& o) { return std::invoke(f, o); })
		{
		}
		double operator()(const T& o) const { return m_f(o); }

	private:
		std::function<double(const T&)> m_f;
	};

	/** One declared key. */
	struct Entry
	{
		std::string key;
		std::string doc;
		/** Empty for a check() entry. */
		std::function<void(
		    T&, const mrpt::config::CConfigFileBase&, const std::string&)>
		    load;
		/** The value as written to INI; absent (not written) when it
		 * returns false. */
		std::function<bool(const T&, std::string&)> save;
	};

	/** A real number in [lo, hi]. */
	OptionTable& real(
	    const std::string& key, double T::*m, Bound lo, Bound hi,
	    const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    { o.*m = readChecked(c, s, key, o.*m, lo(o), hi(o)); },
		    [m](const T& o) { return numberText(o.*m); });
	}

	/** A real number reached through `at` (e.g. a member of a member). */
	OptionTable& realAt(
	    const std::string& key, std::function<double&(T&)> at, Bound lo,
	    Bound hi, const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    { at(o) = readChecked(c, s, key, at(o), lo(o), hi(o)); },
		    [at](const T& o) { return numberText(at(const_cast<T&>(o))); });
	}

	/** An angle stored in radians, written in degrees; range in degrees. */
	OptionTable& angle(
	    const std::string& key, double T::*m, Bound loDeg, Bound hiDeg,
	    const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    {
			    if (isAbsent(c, s, key)) return;
			    o.*m = degToRad(readChecked(c, s, key, 0, loDeg(o), hiDeg(o)));
		    },
		    [m](const T& o) { return angleText(radToDeg(o.*m)); });
	}

	/** An integer (int, unsigned, size_t...) in [lo, hi]. */
	template <class I>
	OptionTable& integer(
	    const std::string& key, I T::*m, Bound lo, Bound hi,
	    const std::string& doc)
	{
		static_assert(std::is_integral_v<I>);
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    {
			    o.*m = static_cast<I>(readCheckedInt(
			        c, s, key, static_cast<int>(o.*m), static_cast<int>(lo(o)),
			        static_cast<int>(hi(o))));
		    },
		    [m](const T& o) { return std::to_string(o.*m); });
	}

	/** A list of real numbers separated by spaces, each in [lo, hi]. */
	OptionTable& reals(
	    const std::string& key, std::vector<double> T::*m, double lo, double hi,
	    const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    { o.*m = readCheckedList(c, s, key, o.*m, lo, hi); },
		    [m](const T& o) { return listText(o.*m); });
	}

	/** true/false (also 1/0, yes/no). */
	OptionTable& flag(
	    const std::string& key, bool T::*m, const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    { o.*m = readCheckedBool(c, s, key, o.*m); },
		    [m](const T& o) { return std::string(o.*m ? "true" : "false"); });
	}

	/** Free text (a name or a path), kept as written. */
	OptionTable& text(
	    const std::string& key, std::string T::*m, const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    { o.*m = c.read_string(s, key, o.*m, false); },
		    [m](const T& o) { return o.*m; });
	}

	/** One of a few words, each standing for a value of `E`. */
	template <class E>
	OptionTable& choice(
	    const std::string& key, E T::*m,
	    const std::vector<std::pair<E, std::string>>& choices,
	    const std::string& doc)
	{
		std::vector<std::string> names;
		for (const auto& ch : choices) names.push_back(ch.second);
		const auto index = [choices](E v)
		{
			for (std::size_t i = 0; i < choices.size(); i++)
				if (choices[i].first == v) return static_cast<int>(i);
			return 0;
		};
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    {
			    o.*m = choices[static_cast<std::size_t>(
			                       readChoice(c, s, key, index(o.*m), names))]
			               .first;
		    },
		    [=](const T& o) { return names[index(o.*m)]; });
	}

	/** A value of `V` written as a name: `fromName` parses it (its
	 * exceptions become ConfigError "[section] key: <what>"), `toName`
	 * writes it. */
	template <class V, class FromName, class ToName>
	OptionTable& named(
	    const std::string& key, V T::*m, FromName fromName, ToName toName,
	    const std::string& doc)
	{
		return add(
		    key, doc,
		    [=](T& o, const auto& c, const std::string& s)
		    {
			    const std::string text =
			        c.read_string(s, key, std::string(toName(o.*m)), false);
			    try
			    {
				    o.*m = fromName(text);
			    }
			    catch (const std::exception& e)
			    {
				    throw ConfigError("[" + s + "] " + key + ": " + e.what());
			    }
		    },
		    [=](const T& o) { return std::string(toName(o.*m)); });
	}

	/** A key of its own kind: `load` reads it into T (it may throw
	 * ConfigError), `save` returns its INI text. */
	OptionTable& custom(
	    const std::string& key,
	    std::function<
	        void(T&, const mrpt::config::CConfigFileBase&, const std::string&)>
	        load,
	    std::function<std::string(const T&)> save, const std::string& doc)
	{
		return add(key, doc, std::move(load), std::move(save));
	}

	/** As custom(), for a key written only when `save` returns true. */
	OptionTable& optional(
	    const std::string& key,
	    std::function<
	        void(T&, const mrpt::config::CConfigFileBase&, const std::string&)>
	        load,
	    std::function<bool(const T&, std::string&)> save,
	    const std::string& doc)
	{
		m_entries.push_back({key, doc, std::move(load), std::move(save)});
		return *this;
	}

	/** The keys of `sub` for the member `m` of T, as if declared here. */
	template <class M>
	OptionTable& embed(M T::*m, const OptionTable<M>& sub)
	{
		for (const auto& e : sub.entries())
		{
			Entry w;
			w.key = e.key;
			w.doc = e.doc;
			w.load = [m, load = e.load](
			             T& o, const mrpt::config::CConfigFileBase& c,
			             const std::string& s) { load(o.*m, c, s); };
			if (e.save)
				w.save = [m, save = e.save](const T& o, std::string& out)
				{ return save(o.*m, out); };
			m_entries.push_back(std::move(w));
		}
		return *this;
	}

	/** A consistency check between keys, run where declared: throws
	 * ConfigError "[section] <message>" when `ok` is false. */
	OptionTable& check(
	    std::function<bool(const T&)> ok, const std::string& message)
	{
		return check(ok, [message](const T&) { return message; });
	}

	/** As check(), the message made from the values read. */
	OptionTable& check(
	    std::function<bool(const T&)> ok,
	    std::function<std::string(const T&)> message)
	{
		Entry e;
		e.load = [=](T& o, const auto&, const std::string& s)
		{
			if (!ok(o)) throw ConfigError("[" + s + "] " + message(o));
		};
		m_entries.push_back(e);
		return *this;
	}

	/** Reads [section] into `o`: unknown keys (not declared nor in
	 * `alsoKnown`), bad values and failed checks throw ConfigError naming
	 * section and key; `o` is then unchanged. */
	void load(
	    T& o, const mrpt::config::CConfigFileBase& c,
	    const std::string& section,
	    const std::vector<std::string>& alsoKnown = {}) const
	{
		auto known = keys();
		known.insert(known.end(), alsoKnown.begin(), alsoKnown.end());
		checkKnownKeys(c, section, known);
		T loaded = o;
		for (const auto& e : m_entries) e.load(loaded, c, section);
		o = std::move(loaded);
	}

	/** Writes every key of `o` to [section], its doc as the line's
	 * comment. */
	void save(
	    const T& o, mrpt::config::CConfigFileBase& c,
	    const std::string& section) const
	{
		std::string value;
		for (const auto& e : m_entries)
			if (!e.key.empty() && e.save(o, value))
				c.write(section, e.key, value, -1, -1, e.doc);
	}

	/** The declared keys, in order. */
	std::vector<std::string> keys() const
	{
		std::vector<std::string> k;
		for (const auto& e : m_entries)
			if (!e.key.empty()) k.push_back(e.key);
		return k;
	}

	/** The declared entries (keys and checks), in order. */
	const std::vector<Entry>& entries() const { return m_entries; }

private:
	template <class Load>
	OptionTable& add(
	    const std::string& key, const std::string& doc, Load load,
	    std::function<std::string(const T&)> save)
	{
		Entry e;
		e.key = key;
		e.doc = doc;
		e.load = [load](
		             T& o, const mrpt::config::CConfigFileBase& c,
		             const std::string& s) { load(o, c, s); };
		e.save = [save](const T& o, std::string& out)
		{
			out = save(o);
			return true;
		};
		m_entries.push_back(std::move(e));
		return *this;
	}

	static bool isAbsent(
	    const mrpt::config::CConfigFileBase& c, const std::string& s,
	    const std::string& key)
	{
		return c.read_string(s, key, "", false).find_first_not_of(" \t\r\n") ==
		       std::string::npos;
	}
	static double degToRad(double d) { return d * M_PI / 180.0; }
	static double radToDeg(double r) { return r * 180.0 / M_PI; }

	std::vector<Entry> m_entries;
};

}  // namespace semnav

/** Defines `Class::loadFromConfigFile` and `Class::saveToConfigFile` (MRPT's
 * CLoadableOptions) by `table`, an expression giving the
 * OptionTable<Class>. */
#define SEMNAV_OPTIONS_FROM_TABLE(Class, table)                       \
	void Class::loadFromConfigFile(                                   \
	    const mrpt::config::CConfigFileBase& c, const std::string& s) \
	{                                                                 \
		(table).load(*this, c, s);                                    \
	}                                                                 \
	void Class::saveToConfigFile(                                     \
	    mrpt::config::CConfigFileBase& c, const std::string& s) const \
	{                                                                 \
		(table).save(*this, c, s);                                    \
	}

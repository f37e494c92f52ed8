/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>

#include <string>

namespace semnav
{
/** An order given by label, object or point:
 * - "go to the nearest <label>" (also "go to nearest <label>"),
 * - "go to <label> <id>" (an object of the map, e.g. "go to wastebasket 3"),
 * - "go to <x> <y>" (metres, world frame; "go to <x>,<y>" too).
 * Case and extra spaces are ignored. */
struct NavCommand
{
	enum class Kind
	{
		NearestLabel,
		Object,
		Point
	};

	Kind kind = Kind::Point;
	Label label = Label::Unknown;
	int objectId = 0;
	double x = 0, y = 0;

	static NavCommand nearest(Label l);
	static NavCommand object(Label l, int id);
	static NavCommand point(double x, double y);

	/** Parses a command; throws UnknownLabelError (listing the known
	 * labels) for an unknown label and NavCommandError for anything else
	 * that is not one of the forms above. */
	static NavCommand parse(const std::string& text);

	/** Canonical text, e.g. "go to the nearest wastebasket". */
	std::string text() const;
};

}  // namespace semnav

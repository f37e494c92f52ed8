/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <stdexcept>
#include <string>

namespace semnav
{
/** Base of every exception thrown by semnav libraries. Apps catch it, print
 * what() as one line and exit with a non-zero code. */
class Error : public std::runtime_error
{
public:
	explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/** An INI file has an unknown section or key, or an out-of-range value. */
class ConfigError : public Error
{
	using Error::Error;
};

/** A scene file (YAML) is malformed or has unknown keys or bad values. */
class SceneError : public Error
{
	using Error::Error;
};

/** A rawlog cannot be opened, or is corrupt or truncated. */
class RawlogError : public Error
{
	using Error::Error;
};

/** A file cannot be read or written. */
class IoError : public Error
{
	using Error::Error;
};

/** A label name is not one of semnav's labels. */
class UnknownLabelError : public Error
{
	using Error::Error;
};

}  // namespace semnav

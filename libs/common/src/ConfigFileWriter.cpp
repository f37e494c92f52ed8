/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/ConfigFileWriter.h>

#include <sstream>

namespace semnav
{
namespace
{
/** Records the keys written to it in order, with their comments. */
class RecordingConfig : public mrpt::config::CConfigFileBase
{
public:
	struct Key
	{
		std::string section, name, value, doc;
	};
	std::vector<Key> keys;

	void getAllSections(std::vector<std::string>& out) const override
	{
		out.clear();
		for (const auto& k : keys)
			if (out.empty() || out.back() != k.section)
				out.push_back(k.section);
	}
	void getAllKeys(const std::string& section, std::vector<std::string>& out)
	    const override
	{
		out.clear();
		for (const auto& k : keys)
			if (k.section == section) out.push_back(k.name);
	}
	void clear() override { keys.clear(); }

protected:
	void writeString(
	    const std::string& section, const std::string& name,
	    const std::string& str) override
	{
		// CConfigFileBase::write() appends the comment as " // doc".
		Key k{section, name, str, ""};
		const auto c = str.find("// ");
		if (c != std::string::npos && (c == 0 || str[c - 1] == ' '))
		{
			k.value = str.substr(0, c);
			k.doc = str.substr(c + 3);
		}
		k.value = trimmed(k.value);
		k.doc = trimmed(k.doc);
		keys.push_back(k);
	}
	std::string readString(
	    const std::string& section, const std::string& name,
	    const std::string& defaultStr, bool) const override
	{
		for (const auto& k : keys)
			if (k.section == section && k.name == name) return k.value;
		return defaultStr;
	}
};

void commentLines(std::ostream& out, const std::string& text)
{
	std::istringstream in(text);
	for (std::string line; std::getline(in, line);)
		out << (line.empty() ? "#" : "# " + line) << "\n";
}
}  // namespace

std::string configText(
    const std::vector<ConfigSection>& sections, const std::string& header)
{
	std::ostringstream out;
	commentLines(out, header);
	for (const auto& s : sections)
	{
		RecordingConfig rec;
		s.options->saveToConfigFile(rec, s.name);
		std::string current;
		for (const auto& k : rec.keys)
		{
			if (k.section != current)
			{
				if (out.tellp() > 0) out << "\n";
				out << "[" << k.section << "]\n";
				current = k.section;
			}
			if (!k.doc.empty()) commentLines(out, k.doc);
			out << k.name << " = " << k.value << "\n";
		}
	}
	return out.str();
}

void writeConfigFile(
    const std::string& path, const std::vector<ConfigSection>& sections,
    const std::string& header)
{
	writeFileAtomically(path, configText(sections, header));
}

}  // namespace semnav

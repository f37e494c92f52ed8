/* semnav: semantic navigation from tilting-laser sweeps */
// Writes every shipped config file (config/*.ini) from the code's defaults
// and its overrides (ShippedConfigs.cpp): write_shipped_configs [DIR]
// (default: the source tree's config/).
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "ShippedConfigs.h"

int main(int argc, char** argv)
{
	try
	{
		const std::string dir =
		    argc > 1 ? argv[1] : std::string(SEMNAV_SOURCE_DIR) + "/config";
		for (const auto& spec : semnav::test::shippedConfigs())
		{
			const std::string path = dir + "/" + spec.file;
			std::ifstream in(path);
			std::stringstream current;
			current << in.rdbuf();
			semnav::writeFileAtomically(
			    path, semnav::test::expectedText(spec, current.str()));
			std::cout << path << "\n";
		}
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << e.what() << "\n";
		return 1;
	}
}

/* semnav: semantic navigation from tilting-laser sweeps */
// A shared library that is no semnav plugin: it exports a function, none of
// SEMNAV_ROBOT_BASE_PLUGIN's.
extern "C" __attribute__((visibility("default"))) int notAPlugin()
{
	return 1;
}

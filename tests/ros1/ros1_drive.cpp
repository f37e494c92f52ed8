/* semnav: semantic navigation from tilting-laser sweeps */
// ros1_drive NODE V W: a Ros1Base commanding (V, W) every 0.1 s until
// killed, as semnav driving; the tests SIGKILL it to check the base's own
// watchdog. Prints "driving" once the first command is sent.
#include <semnav/ros1/Ros1Base.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <thread>

int main(int argc, char** argv)
{
	if (argc != 4)
	{
		std::cerr << "usage: ros1_drive NODE V W\n";
		return 2;
	}
	semnav::Ros1Base::TOptions o;
	o.nodeName = argv[1];
	semnav::Ros1Base base(o);
	const double v = std::atof(argv[2]), w = std::atof(argv[3]);
	bool announced = false;
	for (;;)
	{
		if (base.setVelocity(v, w) && !announced)
		{
			std::cout << "driving" << std::endl;
			announced = true;
		}
		std::this_thread::sleep_for(std::chrono::milliseconds(100));
	}
}

/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/planning/GridExport.h>

#include <limits>
#include <nlohmann/json.hpp>

namespace semnav
{
std::string npyBytes(
    const void* data, std::size_t elementSize, const std::string& descr,
    int rows, int cols)
{
	std::string header =
	    "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" +
	    std::to_string(rows) + ", " + std::to_string(cols) + "), }";
	// Magic (6) + version (2) + length (2) + header, padded to 64 bytes.
	const std::size_t unpadded = 10 + header.size() + 1;
	header.append((64 - unpadded % 64) % 64, ' ');
	header += '\n';
	std::string out("\x93NUMPY\x01\x00", 8);
	const auto len = static_cast<uint16_t>(header.size());
	out += static_cast<char>(len & 0xFF);
	out += static_cast<char>(len >> 8);
	out += header;
	out.append(
	    static_cast<const char*>(data),
	    elementSize * static_cast<std::size_t>(rows) * cols);
	return out;
}

void exportPlanGrids(
    const std::string& prefix, const SemanticPlanner::Plan& plan)
{
	const GridGeometry& g = plan.u.geometry();
	const double L = plan.u.L();
	std::vector<float> u(g.cellCount());
	for (std::size_t i = 0; i < u.size(); i++)
	{
		const double v = plan.u.values()[i];
		u[i] = v >= L ? std::numeric_limits<float>::infinity()
		              : static_cast<float>(v);
	}
	writeFileAtomically(
	    prefix + "_u.npy",
	    npyBytes(u.data(), sizeof(float), "<f4", g.rows, g.cols));
	const auto mask = plan.goals.mask();
	writeFileAtomically(
	    prefix + "_goal.npy", npyBytes(mask.data(), 1, "|u1", g.rows, g.cols));
	nlohmann::json j;
	j["resolution"] = g.resolution;
	j["origin_x"] = g.originX;
	j["origin_y"] = g.originY;
	j["L"] = L;
	j["start"] = {plan.start.row, plan.start.col};
	j["path"] = nlohmann::json::array();
	for (const auto& c : plan.path.cells) j["path"].push_back({c.row, c.col});
	writeFileAtomically(prefix + "_meta.json", j.dump(1) + "\n");
}

}  // namespace semnav

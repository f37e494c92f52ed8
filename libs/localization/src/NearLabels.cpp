/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/localization/NearLabels.h>
#include <semnav/perception/LabeledSweep.h>

#include <cmath>

namespace semnav
{
void NearLabels::insert(const LabeledSweep& s, const mrpt::poses::CPose2D& pose)
{
	const double r2 = m_range * m_range, inv = 1.0 / m_resolution;
	const double c = std::cos(pose.phi()), sn = std::sin(pose.phi());
	for (int r = 0; r < s.labels.rows; r++)
		for (int col = 0; col < s.labels.cols; col++)
		{
			const Label l = s.label(r, col);
			if (l == Label::Unknown ||
			    (!s.validMask.empty() && !s.validMask.at<uint8_t>(r, col)))
				continue;
			const auto& p = s.points.at<cv::Vec3f>(r, col);
			if (!std::isfinite(p[0]) || !std::isfinite(p[1]) ||
			    double(p[0]) * p[0] + double(p[1]) * p[1] > r2)
				continue;
			const double wx = pose.x() + c * p[0] - sn * p[1];
			const double wy = pose.y() + sn * p[0] + c * p[1];
			LabelSet::mask_t& m = m_cells[key(
			    static_cast<std::int64_t>(std::floor(wx * inv)),
			    static_cast<std::int64_t>(std::floor(wy * inv)))];
			LabelSet set(m);
			set.insert(l);
			m = set.mask();
		}
}

std::vector<float> NearLabels::layer(const GridGeometry& g) const
{
	std::vector<float> out(g.cellCount(), 0.0f);
	const double inv = 1.0 / m_resolution;
	for (int cy = 0; cy < g.rows; cy++)
	{
		const auto ky =
		    static_cast<std::int64_t>(std::floor(g.centerY(cy) * inv));
		for (int cx = 0; cx < g.cols; cx++)
		{
			const auto it = m_cells.find(
			    key(static_cast<std::int64_t>(std::floor(g.centerX(cx) * inv)),
			        ky));
			if (it != m_cells.end())
				out[g.index(cy, cx)] = static_cast<float>(it->second);
		}
	}
	return out;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/sim/Scene.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
/** Whether the vertical segment at (x, y) from zlo to zhi meets `part`. */
bool solidAt(
    const ScenePrimitive& part, double x, double y, double zlo, double zhi)
{
	auto overlaps = [&](double lo, double hi)
	{ return lo <= zhi && hi >= zlo; };
	if (const auto* b = std::get_if<BoxShape>(&part))
	{
		const double dx = x - b->center.x, dy = y - b->center.y;
		const double c = std::cos(b->yaw), s = std::sin(b->yaw);
		return std::abs(c * dx + s * dy) <= b->size.x / 2 &&
		       std::abs(-s * dx + c * dy) <= b->size.y / 2 &&
		       overlaps(
		           b->center.z - b->size.z / 2, b->center.z + b->size.z / 2);
	}
	if (const auto* cy = std::get_if<CylinderShape>(&part))
		return std::hypot(x - cy->center.x, y - cy->center.y) <= cy->radius &&
		       overlaps(
		           cy->center.z - cy->height / 2,
		           cy->center.z + cy->height / 2);
	if (const auto* st = std::get_if<StairsShape>(&part))
	{
		const double dx = x - st->origin.x, dy = y - st->origin.y;
		const double c = std::cos(st->yaw), s = std::sin(st->yaw);
		const double u = c * dx + s * dy;
		if (u < 0 || u > st->steps * st->run ||
		    std::abs(-s * dx + c * dy) > st->width / 2)
			return false;
		const int k = std::min(static_cast<int>(u / st->run), st->steps - 1);
		return overlaps(0, (k + 1) * st->rise);
	}
	return false;  // terrain: ground
}
}  // namespace

std::optional<std::size_t> Scene::obstacleAt(double x, double y) const
{
	const double top = std::max(sensor.mount.z, kBodyBottom);
	for (std::size_t i = 0; i < objects.size(); i++)
		for (const auto& part : objects[i].parts)
			if (solidAt(part, x, y, kBodyBottom, top)) return i;
	return std::nullopt;
}

namespace
{
mrpt::math::TPoint2D partCentre(const ScenePrimitive& part)
{
	if (const auto* b = std::get_if<BoxShape>(&part))
		return {b->center.x, b->center.y};
	if (const auto* c = std::get_if<CylinderShape>(&part))
		return {c->center.x, c->center.y};
	if (const auto* st = std::get_if<StairsShape>(&part))
	{
		const double len = st->steps * st->run;
		return {
		    st->origin.x + std::cos(st->yaw) * len / 2,
		    st->origin.y + std::sin(st->yaw) * len / 2};
	}
	return {0, 0};
}
}  // namespace

mrpt::math::TPoint2D SceneObject::centre() const
{
	if (parts.empty()) return {0, 0};
	if (label != Label::Door) return partCentre(parts.front());
	mrpt::math::TPoint2D sum{0, 0};
	for (const auto& p : parts)
	{
		const auto c = partCentre(p);
		sum.x += c.x;
		sum.y += c.y;
	}
	return {sum.x / parts.size(), sum.y / parts.size()};
}

}  // namespace semnav

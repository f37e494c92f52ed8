/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, step 4: the rules on each surface (ground, ceiling, wall,
 * door, obstacle). */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "RuleClassifierDetail.h"

namespace semnav
{
using namespace detail::rules;

namespace
{
/** A surface within this many rows of the image's bottom edge is cut by
 * the field of view there (the outermost rows have no normals). */
constexpr int kBorderRows = 3;
}  // namespace

std::size_t RuleClassifier::applyRules(double zg, LabeledSweep& out)
{
	std::vector<uint8_t> isCeiling;
	const std::size_t ceilPixels = labelGroundAndCeiling(zg, isCeiling, out);
	const std::vector<int> wallCandidate = findWalls(out);
	labelDoorsAndWalls(zg, wallCandidate, isCeiling);
	const TOptions& o = m_options;
	for (Surface& s : m_surfaces)
		if (s.label == kNoLabel && s.count >= o.minSurfacePixels &&
		    s.maxP[2] > zg + o.groundTolerance)
			s.label = lab(Label::Obstacle);
	unlabelPlaneFragments();
	return ceilPixels;
}

std::size_t RuleClassifier::labelGroundAndCeiling(
    double zg, std::vector<uint8_t>& isCeiling, LabeledSweep& out)
{
	const TOptions& o = m_options;
	const std::size_t ns = m_surfaces.size();
	isCeiling.assign(ns, 0);
	double ceilSum = 0;
	std::size_t ceilPixels = 0;
	for (std::size_t i = 0; i < ns; i++)
	{
		Surface& s = m_surfaces[i];
		if (s.count < o.minSurfacePixels) continue;
		if (s.orient == kUp &&
		    std::abs(s.centroid[2] - zg) <= o.groundTolerance)
			s.label = lab(Label::Floor);  // ground; typed in step 6
		else if (s.orient == kDown && s.centroid[2] >= zg + o.ceilingMinHeight)
		{
			s.label = lab(Label::Ceiling);
			isCeiling[i] = 1;
			ceilSum += s.centroid[2] * s.count;
			ceilPixels += s.count;
		}
	}
	if (ceilPixels > 0) out.ceilingZ = ceilSum / ceilPixels;
	return ceilPixels;
}

std::vector<int> RuleClassifier::findWalls(const LabeledSweep& out) const
{
	const TOptions& o = m_options;
	const std::size_t ns = m_surfaces.size();
	// Wall size rules on each vertical surface and on its loose group (the
	// pieces of one wall that noise or a plane step cut apart).
	// The field of view cuts surfaces near the robot at the image's bottom
	// rows (theta -15 deg); the height seen there is a lower bound, so
	// such a surface counts from the ground. A long one must rise above
	// what a robot sees over: a low garden wall is an obstacle.
	const double zg = out.groundZ;
	auto wallSized = [&](const Surface& s)
	{
		const bool cutAtBottom = s.minR <= kBorderRows;
		const double height =
		    cutAtBottom ? std::max<double>(s.height, s.maxP[2] - zg) : s.height;
		const bool tall = height >= o.wallMinHeight;
		const bool toCeiling =
		    out.ceilingZ && s.maxP[2] >= *out.ceilingZ - o.wallCeilingGap;
		// A narrow one only when tall: the end face of a wall at an
		// opening, not a pole or a chair's leg.
		if (s.width < o.wallMinWidth) return tall || toCeiling;
		const bool longWall =
		    s.width >= o.wallMinLength && s.maxP[2] >= zg + o.wallLongMinReach;
		return tall || toCeiling || longWall;
	};
	// (Indexed through looseIdx: few of the loose groups are used.)
	std::vector<int> looseIdx(m_loose.size(), -1);
	std::vector<Surface> loose;
	for (std::size_t i = 0; i < ns; i++)
	{
		const Surface& s = m_surfaces[i];
		if (s.orient != kVertical || s.count < o.minSurfacePixels) continue;
		int& li = looseIdx[m_surfLoose[i]];
		if (li < 0)
		{
			li = static_cast<int>(loose.size());
			loose.emplace_back();
		}
		Surface& g = loose[li];
		if (g.count == 0)
		{
			g = s;
			continue;
		}
		g.count += s.count;
		g.sumP += s.sumP;
		g.sumN += s.sumN;
		for (int k = 0; k < 3; k++)
		{
			g.minP[k] = std::min(g.minP[k], s.minP[k]);
			g.maxP[k] = std::max(g.maxP[k], s.maxP[k]);
		}
		g.minR = std::min(g.minR, s.minR);
	}
	std::vector<uint8_t> looseWall(loose.size(), 0);
	for (std::size_t k = 0; k < loose.size(); k++)
		if (loose[k].count > 0)
		{
			finishSurface(loose[k]);
			looseWall[k] = wallSized(loose[k]);
		}
	std::vector<int> wallCandidate(ns, 0);
	for (std::size_t i = 0; i < ns; i++)
	{
		const Surface& s = m_surfaces[i];
		if (s.orient != kVertical || s.count < o.minSurfacePixels) continue;
		wallCandidate[i] = wallSized(s) || looseWall[looseIdx[m_surfLoose[i]]];
	}
	return wallCandidate;
}

bool RuleClassifier::singleSideHolds(
    const Surface& s, const DoorCheck& dc) const
{
	// With one wall side only (the others cut by the field of view), that
	// one is all the evidence: it must hold along door_single_side_fraction
	// (searched farther, see checkDoor(); slivers are searched as before).
	if (!doorSized(s)) return true;
	const double f = m_options.doorMinSideFraction;
	const int walls = (dc.left >= f) + (dc.right >= f) + (dc.top >= f);
	return walls != 1 || std::max({dc.left, dc.right, dc.top}) >=
	                         m_options.doorSingleSideFraction;
}

bool RuleClassifier::lintelAndOneSide(
    const Surface& s, const DoorCheck& dc) const
{
	// A leaf under a lintel with a wall on one side: the other side's wall
	// may be hidden by the reveal of a thick wall seen at an angle, be a
	// corner, or lie far behind. (Its size, bottom and offset are checked
	// as for any candidate.)
	const TOptions& o = m_options;
	const double f = o.doorMinSideFraction;
	return o.doorLintelOneSide && doorSized(s) && !dc.topFov && dc.top >= f &&
	       (dc.left >= f || dc.right >= f);
}

bool RuleClassifier::lintelSeenIn3d(const Surface& s, const DoorCheck& dc) const
{
	// A leaf seen close up is cut by the field of view at its top and one
	// side, and its lintel lies beside it in the image: the image's sides
	// do not tell. Walls of its plane above it in 3D do.
	const TOptions& o = m_options;
	return o.doorLintel3d && doorSized(s) &&
	       (dc.topFov || dc.leftFov || dc.rightFov) &&
	       dc.lintelAbove >= o.doorMinSideFraction;
}

bool RuleClassifier::recessedLeafBeside(
    const Surface& s, const DoorCheck& dc, double zg) const
{
	// A leaf seen close up beside the robot fills the sweep's side from
	// its bottom row to its top row: only one side is in view, and its
	// probes find the wall beside the frame along part of it (the rest is
	// the frame's reveal). Standing well off that wall, it is a leaf set
	// back in its frame, not a piece of the wall.
	// (It fills the image's rows, and its top, below its lintel, is no
	// higher than a door: a piece of wall high up at the side is not.)
	const TOptions& o = m_options;
	const int K = o.doorSearchPixels;
	if (o.doorRecessedLeafOffset <= 0 || !doorSized(s) || !dc.topFov ||
	    !dc.bottomFov || dc.leftFov == dc.rightFov || s.minR > K ||
	    s.maxR < m_rows - 1 - K || s.maxP[2] > zg + o.doorMaxHeight)
		return false;
	const double side = dc.leftFov ? dc.right : dc.left;
	return side >= o.doorRecessedLeafSideFraction &&
	       dc.maxOffset >= o.doorRecessedLeafOffset;
}

bool RuleClassifier::recessedLeafFramed(const DoorCheck& dc) const
{
	// A leaf set back in its frame, seen whole: the frame's reveals and
	// the leaf's own shadow hide part of the walls around it (a double
	// door seen at an angle, a far leaf under a thin lintel), but a piece
	// of wall does not stand that far off the walls around it.
	const TOptions& o = m_options;
	const double g = o.doorRecessedFrameSideFraction;
	return g > 0 && o.doorRecessedLeafOffset > 0 &&
	       dc.maxOffset >= o.doorRecessedLeafOffset && dc.wholeFrame(g);
}

bool RuleClassifier::narrowAndFramed(
    const Surface& s, const DoorCheck& dc) const
{
	// The seam and lintel splits cut part of a leaf out of its wall, and
	// the rest of the leaf stays with the wall: the piece is narrower than
	// a door, with wall (its own leaf's rest, then the frame) close around
	// it on three sides. Only seen close up (cut by the field of view at
	// its bottom): far off, narrow framed pieces are panels and reveals.
	const TOptions& o = m_options;
	const double g = o.doorSingleSideFraction;
	return o.doorFramedMinWidth > 0 && s.width >= o.doorFramedMinWidth &&
	       dc.bottomFov && dc.wholeFrame(g);
}

void RuleClassifier::labelDoorsAndWalls(
    double zg, const std::vector<int>& wallCandidate,
    const std::vector<uint8_t>& isCeiling)
{
	const TOptions& o = m_options;
	const std::size_t ns = m_surfaces.size();
	const double f = o.doorMinSideFraction;
	for (std::size_t i = 0; i < ns; i++)
	{
		Surface& s = m_surfaces[i];
		if (s.orient != kVertical || s.count < o.minSurfacePixels) continue;
		bool door = false;
		const bool framedWidth =
		    s.width > o.doorMaxWidth && s.width <= o.doorFramedMaxWidth;
		if ((s.width <= o.doorMaxWidth || framedWidth) &&
		    s.height <= o.doorMaxHeight)
		{
			// Where the field of view cuts the surface (image border) its
			// extent and neighbours there are unknown: accepted when
			// door_allow_truncation, but at least one side must be a wall.
			const DoorCheck dc =
			    checkDoor(static_cast<int>(i), wallCandidate, isCeiling);
			const bool t = o.doorAllowTruncation;
			const bool sides =
			    ((dc.left >= f || (t && dc.leftFov)) &&
			     (dc.right >= f || (t && dc.rightFov)) &&
			     (dc.top >= f || (t && dc.topFov)) &&
			     (dc.left >= f || dc.right >= f) && singleSideHolds(s, dc)) ||
			    lintelAndOneSide(s, dc) || lintelSeenIn3d(s, dc) ||
			    recessedLeafBeside(s, dc, zg) || recessedLeafFramed(dc);
			// A side hidden by something nearer (a reveal, furniture)
			// bounds the extent seen there as the field of view does.
			const bool shown = doorSized(s);
			const bool height =
			    s.height >= o.doorMinHeight ||
			    (t && (dc.topFov || dc.bottomFov)) ||
			    (shown && dc.bottomHidden && s.maxP[2] >= zg + o.doorMinHeight);
			const bool width = s.width >= o.doorMinWidth ||
			                   narrowAndFramed(s, dc) ||
			                   (t && (dc.leftFov || dc.rightFov)) ||
			                   (shown && (dc.leftHidden || dc.rightHidden));
			const bool bottom = s.minP[2] <= zg + o.doorBottomTolerance ||
			                    (t && dc.bottomFov) ||
			                    (shown && dc.bottomHidden);
			// Wider than a door: only with its whole frame seen.
			const bool framed = !framedWidth || dc.wholeFrame(f);
			const bool offset = dc.maxOffset >= o.doorMinOffset ||
			                    (dc.maxOffset >= o.doorFramedMinOffset &&
			                     dc.wholeFrame(o.doorFramedSideFraction));
			door = sides && framed && height && width && bottom && offset;
			MRPT_LOG_DEBUG_FMT(
			    "door candidate %zu: %d px, rows %d-%d cols %d-%d, width %.2f "
			    "height %.2f z %.2f..%.2f; walls left %.2f right %.2f top "
			    "%.2f, fov %d%d%d%d, hidden %d%d%d, offset %.3f -> "
			    "%s%s%s%s%s%s",
			    i, s.count, s.minR, s.maxR, s.minC, s.maxC, s.width, s.height,
			    s.minP[2], s.maxP[2], dc.left, dc.right, dc.top, dc.leftFov,
			    dc.rightFov, dc.topFov, dc.bottomFov, dc.leftHidden,
			    dc.rightHidden, dc.bottomHidden, dc.maxOffset,
			    door ? "door" : "no", sides ? "" : " sides",
			    height ? "" : " height", width ? "" : " width",
			    bottom ? "" : " bottom", offset ? "" : " offset");
		}
		else
			MRPT_LOG_DEBUG_FMT(
			    "large surface %zu: %d px, rows %d-%d cols %d-%d, width %.2f "
			    "height %.2f z %.2f..%.2f",
			    i, s.count, s.minR, s.maxR, s.minC, s.maxC, s.width, s.height,
			    s.minP[2], s.maxP[2]);
		if (door)
			s.label = lab(Label::Door);
		else if (wallCandidate[i])
			s.label = lab(Label::Wall);
	}
}

void RuleClassifier::unlabelPlaneFragments()
{
	const TOptions& o = m_options;
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const std::size_t ns = m_surfaces.size();
	// A piece next to a wall or ceiling that lies on its plane (its box
	// within leftover_plane_tolerance_m of it) is a fragment of that
	// surface cut off by noisy normals, not an obstacle: its pixels are
	// left to step 5, which joins them to the plane they lie on.
	std::vector<uint8_t> tested(ns, 0);
	auto onPlane = [&](const Surface& a, const Surface& w)
	{
		const double d = w.planeD();
		// A vertical sliver narrower than a wall (the corner where two
		// walls meet) by its centroid, whatever its normal.
		if (a.orient == kVertical && a.width < o.wallMinWidth &&
		    std::abs(w.normal.dot(a.centroid) - d) <= o.leftoverPlaneTolerance)
			return true;
		if (a.normal.dot(w.normal) < std::cos(o.doorMaxAngle * 2)) return false;
		for (int k = 0; k < 8; k++)
		{
			const cv::Vec3d c(
			    (k & 1) ? a.maxP[0] : a.minP[0],
			    (k & 2) ? a.maxP[1] : a.minP[1],
			    (k & 4) ? a.maxP[2] : a.minP[2]);
			if (std::abs(w.normal.dot(c) - d) > o.leftoverPlaneTolerance)
				return false;
		}
		return true;
	};
	auto planar = [&](int t) { return tested[t] == 3; };
	// 1: an obstacle piece not yet demoted; 3: a wall.
	for (std::size_t i = 0; i < ns; i++)
		tested[i] = m_surfaces[i].label == lab(Label::Obstacle) ? 1
		            : m_surfaces[i].label == lab(Label::Wall)   ? 3
		                                                        : 0;
	for (int p = 0; p < n; p++)
	{
		const int s = m_surf[p];
		if (s < 0 || tested[s] != 1) continue;
		const int r = RO[p], c = CO[p];
		const int nb[4] = {
		    c > 0 ? p - 1 : -1, c + 1 < cols ? p + 1 : -1,
		    r > 0 ? p - cols : -1, r + 1 < rows ? p + cols : -1};
		for (int q : nb)
		{
			const int t = q >= 0 ? m_surf[q] : -1;
			if (t < 0 || t == s || !planar(t)) continue;
			if (onPlane(m_surfaces[s], m_surfaces[t]))
			{
				tested[s] = 2;
				m_surfaces[s].label = kNoLabel;
				break;
			}
		}
	}
}

namespace
{
/** The door rule's probes stop this many pixels away, however close. */
constexpr int kMaxDoorSearchPixels = 60;

/** A door candidate's outline in the image: per row of its box its first
 * and last column, per column its top row, and its lowest and highest
 * pixels. */
struct DoorOutline
{
	std::vector<int> rowMin, rowMax, colMin, colMax;
	int lowest = -1, highest = -1;
};

/** The outline of the pixels of surface `self` (ids `surf`, image `cols`
 * wide) in rows minR..maxR and columns minC..maxC. */
DoorOutline outlineOf(
    const int* surf, const cv::Vec3f* P, int cols, int minR, int maxR, int minC,
    int maxC, int self)
{
	const int nr = maxR - minR + 1, nc = maxC - minC + 1;
	DoorOutline o;
	o.rowMin.assign(nr, cols);
	o.rowMax.assign(nr, -1);
	o.colMin.assign(nc, -1);
	o.colMax.assign(nc, -1);
	float zLo = std::numeric_limits<float>::max(), zHi = -zLo;
	for (int r = minR; r <= maxR; r++)
		for (int c = minC; c <= maxC; c++)
		{
			if (surf[r * cols + c] != self) continue;
			const float z = P[r * cols + c][2];
			if (z < zLo)
			{
				zLo = z;
				o.lowest = r * cols + c;
			}
			if (z > zHi)
			{
				zHi = z;
				o.highest = r * cols + c;
			}
			o.rowMin[r - minR] = std::min(o.rowMin[r - minR], c);
			o.rowMax[r - minR] = std::max(o.rowMax[r - minR], c);
			if (o.colMin[c - minC] < 0) o.colMin[c - minC] = r;
			o.colMax[c - minC] = std::max(o.colMax[c - minC], r);
		}
	return o;
}

/** Shares of a door candidate's left, right and bottom edges hidden by
 * something in front: beyond the edge pixel (stepping dr, dc), the first
 * pixel with a point, of another surface, within `reach` pixels, is
 * nearer to the sensor by `margin`. */
struct DoorOcclusion
{
	double left = 0, right = 0, bottom = 0;
};

DoorOcclusion occlusionOf(
    const DoorOutline& o, const int* surf, const float* ranges, int rows,
    int cols, int minR, int minC, int self, int reach, float margin)
{
	auto hidden = [&](int r, int c, int dr, int dc)
	{
		const float d = ranges[r * cols + c];
		if (!(d > 0)) return false;
		for (int k = 1; k <= reach; k++)
		{
			const int rr = r + k * dr, cc = c + k * dc;
			if (rr < 0 || rr >= rows || cc < 0 || cc >= cols) return false;
			const int q = rr * cols + cc;
			if (surf[q] == self) return false;
			if (!(ranges[q] > 0)) continue;
			return ranges[q] < d - margin;
		}
		return false;
	};
	DoorOcclusion res;
	int left = 0, right = 0, bottom = 0, nRows = 0, nCols = 0;
	for (std::size_t i = 0; i < o.rowMin.size(); i++)
	{
		if (o.rowMax[i] < 0) continue;
		nRows++;
		const int r = minR + static_cast<int>(i);
		// Lower columns are on the robot's right.
		right += hidden(r, o.rowMin[i], 0, -1);
		left += hidden(r, o.rowMax[i], 0, 1);
	}
	for (std::size_t j = 0; j < o.colMin.size(); j++)
	{
		if (o.colMin[j] < 0) continue;
		nCols++;
		bottom += hidden(o.colMin[j], minC + static_cast<int>(j), -1, 0);
	}
	if (nRows > 0) res.left = double(left) / nRows;
	if (nRows > 0) res.right = double(right) / nRows;
	if (nCols > 0) res.bottom = double(bottom) / nCols;
	return res;
}
/** Share of a leaf's width (kLintelSlice slices along its plane, between
 * its box's ends; normal `n`, box lo..hi) over which one of `hits` lies
 * above its top (a wall of its plane: its lintel). */
double lintelShareOf(
    const cv::Vec3d& n, const cv::Vec3f& lo, const cv::Vec3f& hi,
    const cv::Vec3f* P, const std::vector<int>& hits)
{
	constexpr double kLintelSlice = 0.05, kAboveMargin = 0.05;
	const double ax = -n[1], ay = n[0];
	// (The box's corners project onto the plane's direction within the
	// ends of the leaf's footprint.)
	double uLo = 1e30, uHi = -1e30;
	for (const float x : {lo[0], hi[0]})
		for (const float y : {lo[1], hi[1]})
		{
			uLo = std::min(uLo, ax * x + ay * y);
			uHi = std::max(uHi, ax * x + ay * y);
		}
	const int nb = std::max(1, static_cast<int>((uHi - uLo) / kLintelSlice));
	std::vector<uint8_t> covered(nb, 0);
	for (const int q : hits)
	{
		const double u = ax * P[q][0] + ay * P[q][1];
		if (P[q][2] < hi[2] - kAboveMargin || u <= uLo || u >= uHi) continue;
		covered[std::min(nb - 1, static_cast<int>((u - uLo) / kLintelSlice))] =
		    1;
	}
	return static_cast<double>(std::count(covered.begin(), covered.end(), 1)) /
	       nb;
}
/** Rows and columns of a door outline whose probes found wall beside it
 * (left, right) and above it (top), or ran out of the image (*Border). */
struct SideCounts
{
	int left = 0, right = 0, top = 0, rows = 0, cols = 0;
	int leftBorder = 0, rightBorder = 0, topBorder = 0;
};

/** Probes each row's ends and each column's top of outline `o` (its first
 * row / column minR / minC) with probe(r, c, dr, dc, ceilingOk, border). */
template <typename Probe>
SideCounts countSides(const DoorOutline& o, int minR, int minC, Probe&& probe)
{
	SideCounts n;
	const int nr = static_cast<int>(o.rowMin.size());
	const int nc = static_cast<int>(o.colMax.size());
	for (int i = 0; i < nr; i++)
	{
		if (o.rowMax[i] < 0) continue;
		n.rows++;
		const int r = minR + i;
		bool border = false;
		// Lower columns are on the robot's right.
		if (probe(r, o.rowMin[i], 0, -1, false, border))
			n.right++;
		else if (border)
			n.rightBorder++;
		border = false;
		if (probe(r, o.rowMax[i], 0, 1, false, border))
			n.left++;
		else if (border)
			n.leftBorder++;
	}
	for (int j = 0; j < nc; j++)
	{
		if (o.colMax[j] < 0) continue;
		n.cols++;
		bool border = false;
		if (probe(o.colMax[j], minC + j, 1, 0, true, border))
			n.top++;
		else if (border)
			n.topBorder++;
	}
	return n;
}

}  // namespace

RuleClassifier::DoorCheck RuleClassifier::checkDoor(
    int self, const std::vector<int>& wallCandidate,
    const std::vector<uint8_t>& isCeiling) const
{
	const Surface& door = m_surfaces[self];
	DoorCheck res;
	const int cols = m_cols, rows = m_rows;
	const double cosMax = std::cos(m_options.doorMaxAngle);
	const double dDoor = door.planeD();
	std::vector<int8_t> compat(m_surfaces.size(), -1);
	auto wallOk = [&](int s)
	{
		if (s < 0 || !wallCandidate[s]) return false;
		if (compat[s] < 0)
		{
			const Surface& w = m_surfaces[s];
			const double off = std::abs(door.normal.dot(w.centroid) - dDoor);
			compat[s] = w.normal.dot(door.normal) >= cosMax &&
			                    off <= m_options.doorMaxOffset
			                ? 1
			                : 0;
			if (compat[s]) res.maxOffset = std::max(res.maxOffset, off);
		}
		return compat[s] == 1;
	};
	const DoorOutline o = outlineOf(
	    m_surf.data(), m_points->ptr<cv::Vec3f>(0), cols, door.minR, door.maxR,
	    door.minC, door.maxC, self);
	const int K = m_options.doorSearchPixels;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	// The probe's reach in pixels: door_search_m at the spacing of the
	// door's own pixels there (a door seen close up spans many pixels, and
	// so do its frame and the gaps beside it), at least K.
	// (Only for a candidate that shows door_search_min_size_m of its width
	// and height: slivers at the field of view's edge keep K.)
	const bool sized = doorSized(door);
	std::vector<int> wallHits;  // wall pixels the probes found (sized)
	auto reach = [&](int r, int c, int dr, int dc)
	{
		if (!sized) return K;
		const int ri = r - dr, ci = c - dc;
		if (ri < 0 || ri >= rows || ci < 0 || ci >= cols ||
		    m_surf[ri * cols + ci] != self)
			return K;
		const double spacing = cv::norm(P[r * cols + c] - P[ri * cols + ci]);
		if (spacing <= 1e-4) return K;
		const double k = m_options.doorSearchDistance / spacing;
		return std::clamp(static_cast<int>(k), K, kMaxDoorSearchPixels);
	};
	// Probes within reach; `border` when the probe runs out of the image
	// (the field of view cuts the surface there).
	auto probe = [&](int r, int c, int dr, int dc, bool ceilingOk, bool& border)
	{
		const int reachPx = reach(r, c, dr, dc);
		for (int k = 1; k <= reachPx; k++)
		{
			const int rr = r + k * dr, cc = c + k * dc;
			if (rr < 0 || rr >= rows || cc < 0 || cc >= cols)
			{
				border = true;
				return false;
			}
			const int s = m_surf[rr * cols + cc];
			if (s == self) return false;
			if (wallOk(s))
			{
				if (sized) wallHits.push_back(rr * cols + cc);
				return true;
			}
			if (ceilingOk && s >= 0 && isCeiling[s]) return true;
		}
		return false;
	};
	const SideCounts n = countSides(o, door.minR, door.minC, probe);
	if (n.rows == 0 || n.cols == 0) return res;
	res.left = double(n.left) / n.rows;
	res.right = double(n.right) / n.rows;
	res.top = double(n.top) / n.cols;
	markFieldOfViewCuts(
	    door, n.leftBorder, n.rightBorder, n.topBorder, o.lowest, o.highest,
	    res);
	if (sized && m_options.doorLintel3d)
		res.lintelAbove =
		    lintelShareOf(door.normal, door.minP, door.maxP, P, wallHits);
	if (m_options.doorOcclusionMargin > 0)
	{
		const DoorOcclusion h = occlusionOf(
		    o, m_surf.data(), m_ranges->ptr<float>(0), rows, cols, door.minR,
		    door.minC, self, K,
		    static_cast<float>(m_options.doorOcclusionMargin));
		const double f = m_options.doorMinSideFraction;
		res.leftHidden = h.left >= f;
		res.rightHidden = h.right >= f;
		res.bottomHidden = h.bottom >= f;
	}
	return res;
}

void RuleClassifier::markFieldOfViewCuts(
    const Surface& door, int leftB, int rightB, int topB, int pLo, int pHi,
    DoorCheck& res) const
{
	const int cols = m_cols, rows = m_rows, K = m_options.doorSearchPixels;
	// Cut by the field of view: the surface reaches the image border (the
	// outermost columns, phi near +-90 deg, have degenerate neighbours and
	// rarely carry normals, hence the wider margin there).
	res.leftFov = leftB > 0 || door.maxC >= cols - 1 - 2 * K;
	res.rightFov = rightB > 0 || door.minC <= 2 * K;
	// Also when its lowest (highest) point lies at the image border: at
	// bearings near +-90 deg the field of view cuts surfaces at a slant.
	auto atBorder = [&](int p)
	{
		if (p < 0) return false;
		const int r = p / cols, c = p % cols;
		return r <= K || r >= rows - 1 - K || c <= 2 * K ||
		       c >= cols - 1 - 2 * K;
	};
	res.topFov = topB > 0 || door.maxR >= rows - 1 - K || atBorder(pHi);
	res.bottomFov = door.minR <= K || atBorder(pLo);
}

}  // namespace semnav

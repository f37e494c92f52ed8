/* semnav: semantic navigation from tilting-laser sweeps
 *
 * Diagnosis tool (branch obstacle4, docs/generated-scenes-log.md "Indoor
 * obstacle"): where the indoor `obstacle` label goes wrong, from the label PNGs
 * that `semnav-perceive --gt-dir D --out O` writes (O/sweep_NNNN_labels.png
 * against O/sweep_NNNN_gt.png, viewer layout, the legend below row 211).
 *
 *   BAND=20 build/scripts/obstacle-confusion OUT/perceive/indoor_{0..19}
 *
 * Prints per scene the obstacle pixel F1 and the F1 without the BAND columns at
 * each side of the image (|phi| near 90 deg, where the sweep's rows nearly
 * coincide), the pixels of each ground-truth class labelled obstacle (and of
 * obstacle labelled each class) inside / outside those bands, and the wall
 * pixels labelled obstacle outside the bands by the connected obstacle-labelled
 * component they lie in: >= 10 % true obstacle ("mixed"), reaching the sweep's
 * lowest line, at most 4 columns wide, other; and the wall pixels labelled
 * obstacle per 10 columns (5 deg of phi) from the image's sides.
 */
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace
{
const int kRows = 211;  // sweep lines; the legend follows
const int kObstacle = 10, kWall = 3;
const char* kNames[] = {"unknown",   "floor",       "ceiling", "wall",
                        "door",      "sidewalk",    "grass",   "stairs",
                        "washbasin", "wastebasket", "obstacle"};

int labelOf(const cv::Vec3b& bgr)
{
	struct C
	{
		int r, g, b;
	};
	static const C cs[] = {{90, 90, 90},  {40, 110, 255}, {255, 220, 0},
	                       {220, 30, 30}, {140, 70, 10},  {200, 200, 200},
	                       {20, 170, 20}, {255, 140, 0},  {0, 220, 220},
	                       {255, 0, 255}, {140, 40, 210}};
	for (int i = 0; i < 11; ++i)
		if (cs[i].r == bgr[2] && cs[i].g == bgr[1] && cs[i].b == bgr[0])
			return i;
	return -1;
}

double f1(long tp, long fp, long fn)
{
	return tp + fp + fn ? 2.0 * tp / (2.0 * tp + fp + fn) : 0.0;
}
}  // namespace

int main(int argc, char** argv)
{
	if (argc < 2)
	{
		std::fprintf(
		    stderr, "usage: BAND=20 obstacle-confusion PERCEIVE_DIR...\n");
		return 2;
	}
	const int band = std::getenv("BAND") ? std::atoi(std::getenv("BAND")) : 20;
	long fpIn[11] = {0}, fpOut[11] = {0}, fnIn[11] = {0}, fnOut[11] = {0};
	long mixed = 0, lowest = 0, narrow = 0, other = 0;
	long byPhi[19] = {0};  // wall labelled obstacle per 10 columns from a side
	double sumAll = 0, sumEx = 0;
	int scenes = 0;
	for (int a = 1; a < argc; ++a)
	{
		long tp = 0, fp = 0, fn = 0, tpE = 0, fpE = 0, fnE = 0;
		for (int s = 0;; ++s)
		{
			char pl[1024], pg[1024];
			std::snprintf(
			    pl, sizeof pl, "%s/sweep_%04d_labels.png", argv[a], s);
			std::snprintf(pg, sizeof pg, "%s/sweep_%04d_gt.png", argv[a], s);
			if (!std::filesystem::exists(pl) || !std::filesystem::exists(pg))
				break;
			const cv::Mat L = cv::imread(pl), G = cv::imread(pg);
			if (L.empty() || G.empty()) break;
			const int W = L.cols;
			cv::Mat lab(kRows, W, CV_8S), gt(kRows, W, CV_8S);
			for (int r = 0; r < kRows; ++r)
				for (int c = 0; c < W; ++c)
				{
					lab.at<schar>(r, c) = labelOf(L.at<cv::Vec3b>(r, c));
					gt.at<schar>(r, c) = labelOf(G.at<cv::Vec3b>(r, c));
				}
			cv::Mat cc, st, ce;
			const int n = cv::connectedComponentsWithStats(
			    lab == kObstacle, cc, st, ce, 8);
			std::vector<long> all(n, 0), trueObst(n, 0);
			for (int r = 0; r < kRows; ++r)
				for (int c = 0; c < W; ++c)
					if (const int k = cc.at<int>(r, c))
					{
						all[k]++;
						if (gt.at<schar>(r, c) == kObstacle) trueObst[k]++;
					}
			for (int r = 0; r < kRows; ++r)
				for (int c = 0; c < W; ++c)
				{
					const int p = lab.at<schar>(r, c), g = gt.at<schar>(r, c);
					if (g <= 0) continue;  // no return / not a class
					const bool in = std::min(c, W - 1 - c) < band;
					if (p == kObstacle && g == kObstacle)
					{
						tp++;
						if (!in) tpE++;
					}
					else if (p == kObstacle)
					{
						fp++;
						if (!in) fpE++;
						(in ? fpIn : fpOut)[g]++;
						if (g == kWall)
							byPhi[std::min(std::min(c, W - 1 - c) / 10, 18)]++;
						if (in || g != kWall) continue;
						const int k = cc.at<int>(r, c);
						const int y = st.at<int>(k, 1), h = st.at<int>(k, 3);
						const int w = st.at<int>(k, 2);
						if (trueObst[k] >= 0.1 * all[k])
							mixed++;
						else if (y + h >= kRows - 1)
							lowest++;
						else if (w <= 4)
							narrow++;
						else
							other++;
					}
					else if (g == kObstacle)
					{
						fn++;
						if (!in) fnE++;
						if (p >= 0) (in ? fnIn : fnOut)[p]++;
					}
				}
		}
		if (tp + fn < 200) continue;
		const std::string name(argv[a]);
		std::printf(
		    "%s obstacle F1 %.3f, without the side bands %.3f (labelled "
		    "obstacle wrongly %ld, in the bands %ld)\n",
		    name.substr(name.find_last_of('/') + 1).c_str(), f1(tp, fp, fn),
		    f1(tpE, fpE, fnE), fp, fp - fpE);
		sumAll += f1(tp, fp, fn);
		sumEx += f1(tpE, fpE, fnE);
		scenes++;
	}
	if (!scenes)
	{
		std::fprintf(
		    stderr,
		    "obstacle-confusion: no scene with >= 200 true obstacle pixels in "
		    "sweep_NNNN_labels.png / sweep_NNNN_gt.png pairs (%d directories, "
		    "first %s)\n",
		    argc - 1, argv[1]);
		return 1;
	}
	std::printf(
	    "mean obstacle F1 %.3f; without %d columns at each side %.3f (%d "
	    "scenes)\n",
	    sumAll / scenes, band, sumEx / scenes, scenes);
	std::printf(
	    "ground truth labelled obstacle: class, in the bands, outside\n");
	for (int i = 0; i < 11; ++i)
		if (fpIn[i] + fpOut[i])
			std::printf("  %s %ld %ld\n", kNames[i], fpIn[i], fpOut[i]);
	std::printf("obstacle labelled as: class, in the bands, outside\n");
	for (int i = 0; i < 11; ++i)
		if (fnIn[i] + fnOut[i])
			std::printf("  %s %ld %ld\n", kNames[i], fnIn[i], fnOut[i]);
	std::printf(
	    "wall labelled obstacle outside the bands, by component: mixed %ld, "
	    "lowest line %ld, narrow %ld, other %ld\n",
	    mixed, lowest, narrow, other);
	std::printf(
	    "wall labelled obstacle per 10 columns (5 deg) from the sides:");
	for (long v : byPhi) std::printf(" %ld", v);
	std::printf("\n");
	return 0;
}

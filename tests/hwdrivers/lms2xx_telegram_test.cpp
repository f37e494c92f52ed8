/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/hwdrivers/Lms2xxTelegramParser.h>

using namespace semnav::lms2xx;

TEST(Lms2xxTelegram, InstallationModeTelegramMatchesSickBytes)
{
	// The "SICK_LMS" installation-mode request as MRPT's CSickLaserSerial
	// documents it, CRC included.
	const std::vector<uint8_t> expected{0x02, 0x00, 0x0A, 0x00, 0x20, 0x00,
	                                    0x53, 0x49, 0x43, 0x4B, 0x5F, 0x4C,
	                                    0x4D, 0x53, 0xBE, 0xC5};
	const std::vector<uint8_t> payload{0x20, 0x00, 'S', 'I', 'C',
	                                   'K',  '_',  'L', 'M', 'S'};
	EXPECT_EQ(buildTelegram(kHostAddress, payload), expected);
}

TEST(Lms2xxTelegram, StatusRequestMatchesSickBytes)
{
	// Status request 0x31 from the LMS2xx telegram listing.
	const std::vector<uint8_t> expected{0x02, 0x00, 0x01, 0x00,
	                                    0x31, 0x15, 0x12};
	EXPECT_EQ(buildTelegram(kHostAddress, {0x31}), expected);
}

TEST(Lms2xxTelegram, MeasuredValuesRoundTripInMmAndCm)
{
	std::vector<uint16_t> mm(361);
	for (std::size_t i = 0; i < mm.size(); i++)
		mm[i] = static_cast<uint16_t>(500 + 17 * i);
	mm[10] = 0x1FFF;
	for (bool mmMode : {true, false})
	{
		const auto bytes = buildMeasuredValues(mm, mmMode);
		ASSERT_EQ(bytes.size(), measuredValuesBytes(361));
		TelegramParser p(kLmsAddress);
		p.feed(bytes.data(), bytes.size());
		auto t = p.next();
		ASSERT_TRUE(t.has_value());
		EXPECT_TRUE(t->crcOk);
		bool isMm = !mmMode;
		const auto r = decodeMeasuredValues(*t, &isMm);
		EXPECT_EQ(isMm, mmMode);
		ASSERT_EQ(r.size(), 361u);
		const float unit = mmMode ? 0.001f : 0.01f;
		EXPECT_FLOAT_EQ(r[0], 500 * unit);
		EXPECT_FLOAT_EQ(r[360], (500 + 17 * 360) * unit);
		EXPECT_FLOAT_EQ(r[10], 8191 * unit);
	}
}

TEST(Lms2xxTelegram, ParserResynchronisesAndFlagsBadCrc)
{
	auto good = buildMeasuredValues(std::vector<uint16_t>(5, 1000), true);
	auto bad = good;
	bad[8] ^= 0x04;
	std::vector<uint8_t> stream{0x06, 0x55, 0x02, 0x13};  // ACK + noise
	stream.insert(stream.end(), bad.begin(), bad.end());
	stream.insert(stream.end(), good.begin(), good.end());
	TelegramParser p(kLmsAddress);
	// Byte by byte, as a slow serial line delivers them.
	for (uint8_t b : stream) p.feed(&b, 1);
	auto t1 = p.next();
	auto t2 = p.next();
	ASSERT_TRUE(t1 && t2);
	EXPECT_FALSE(t1->crcOk);
	EXPECT_TRUE(t2->crcOk);
	EXPECT_FALSE(p.next().has_value());
	EXPECT_EQ(p.skippedBytes(), 4u);
}

TEST(Lms2xxTelegram, DroppedByteCorruptsOnlyThatTelegramsCrc)
{
	auto a = buildMeasuredValues(std::vector<uint16_t>(361, 1234), true);
	const auto b = a;
	a.erase(a.begin() + 100);  // one byte lost on the line
	std::vector<uint8_t> stream = a;
	stream.insert(stream.end(), b.begin(), b.end());
	stream.insert(stream.end(), b.begin(), b.end());
	TelegramParser p(kLmsAddress);
	p.feed(stream.data(), stream.size());
	std::size_t good = 0, badCrc = 0;
	while (auto t = p.next()) (t->crcOk ? good : badCrc)++;
	EXPECT_GE(badCrc, 1u);
	EXPECT_GE(good, 1u);  // resynchronised on a later telegram
}

TEST(Lms2xxTelegram, LineRateLimitAtEachBaudRate)
{
	// 361 ranges = 732 bytes = 7320 bits on the line.
	EXPECT_NEAR(lineRateLimit(38400, 361, 37.5), 38400.0 / 7320.0, 1e-9);
	EXPECT_NEAR(lineRateLimit(9600, 361, 37.5), 9600.0 / 7320.0, 1e-9);
	EXPECT_DOUBLE_EQ(lineRateLimit(500000, 361, 37.5), 37.5);
}

// Tests of the device backends other than UDP: replay CSV (slerp, errors naming file and
// line), the dlopen'ed example plugin, spacenav without a device (and its input-only
// capabilities in a session), the device factory.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <utility>

#include "haptics/device_factory.h"
#include "haptics/halfspace_contact_model.h"
#include "haptics/haptic_cycle.h"
#include "haptics/plugin_device.h"
#include "haptics/replay_device.h"
#include "geometry/rotation_math.h"
#include "haptics/safety_filter.h"
#include "haptics/sim_device.h"
#include "haptics/spacenav_device.h"
#include "haptics/udp_device.h"
#include "haptics/workspace_mapping.h"
#include "test_support.h"
#include "util/error.h"
#include "util/input_files.h"

namespace contactlab {
namespace {

constexpr std::int64_t kMs = 1000000;

void WriteText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// Expects F to throw an Error whose message contains every string in NEEDLES.
template <typename F>
void ExpectErrorMentions(F f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    for (const auto& n : needles) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what() << " lacks " << n;
  }
}

TEST(ReplayDevice, InterpolatesPositionLinearlyAndOrientationBySlerp) {
  testing::TempDir dir;
  const auto file = dir / "traj.csv";
  // 90 degrees about z over one second, moving 3 cm in x.
  WriteText(file, "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n# comment\n\n1.0,0.03,0,0,0.7071067811865476,0,0,0.7071067811865476\n");
  ReplayDevice dev(ReadTrajectoryCsv(file), SimDeviceParams::DefaultCapabilities());
  DeviceState s;
  ASSERT_TRUE(dev.Read(5 * kMs, &s));  // first read = t 0
  EXPECT_LT(s.X_WD.translation.norm(), 1e-15);
  dev.Read(5 * kMs + 250 * kMs, &s);
  EXPECT_NEAR(s.X_WD.translation.x(), 0.0075, 1e-12);
  EXPECT_NEAR(CalcRotationVector(s.X_WD.rotation).z(), M_PI / 8, 1e-9);  // slerp: angle linear in s
  dev.Read(5 * kMs + 2000 * kMs, &s);  // past the end: hold the last pose
  EXPECT_NEAR(s.X_WD.translation.x(), 0.03, 1e-15);
  EXPECT_TRUE(dev.finished());
}

// A recording at 1 kHz (a session log) replays at any loop rate: read at 10 kHz, every pose is
// the linear interpolation of the two recorded samples around it (computed here from the
// samples themselves), and the reads that fall on a sample give that sample.
TEST(ReplayDevice, ARecordingAtOneKilohertzReplaysAtTenKilohertzBetweenItsSamples) {
  testing::TempDir dir;
  const auto file = dir / "traj.csv";
  std::ofstream out(file);
  out << "t,x,y,z,qw,qx,qy,qz\n";
  auto recorded = [](int k) { return Eigen::Vector3d(0.01 * std::sin(2 * M_PI * 1e-3 * k), 1e-5 * k * k, 0); };
  for (int k = 0; k <= 100; ++k) {
    const Eigen::Vector3d p = recorded(k);
    char row[160];
    std::snprintf(row, sizeof row, "%.3f,%.17g,%.17g,%.17g,1,0,0,0\n", 1e-3 * k, p.x(), p.y(), p.z());
    out << row;
  }
  out.close();
  ReplayDevice dev(ReadTrajectoryCsv(file), SimDeviceParams::DefaultCapabilities());
  DeviceState s;
  constexpr std::int64_t kPeriod10k = 100'000;  // ns
  for (int i = 0; i <= 1000; ++i) {
    ASSERT_TRUE(dev.Read(7 * kMs + i * kPeriod10k, &s));  // a new pose every cycle
    const int k = i / 10;
    const double u = (i % 10) / 10.0;
    const Eigen::Vector3d expected = i == 1000 ? recorded(100) : (1 - u) * recorded(k) + u * recorded(k + 1);
    EXPECT_LT((s.X_WD.translation - expected).norm(), 1e-12) << "read " << i;
  }
}

// A device that reports slower than the loop (udp, spacenav, a plugin: 1 kHz or less) is held:
// the cycles between two of its samples see the newest sample (zero-order hold; interpolating
// toward the next sample would wait for it, a sample's delay), and the safety filter does not
// call it silent (its timeout is 50 ms). Here a 1 kHz device in a 10 kHz loop.
class EveryTenthRead final : public HapticDevice {
 public:
  std::string_view name() const override { return "slow"; }
  DeviceCapabilities capabilities() const override { return SimDeviceParams::DefaultCapabilities(); }
  bool Read(std::int64_t now_ns, DeviceState* out) override {
    if (reads_++ % 10 != 0) return false;
    out->X_WD = Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.03 - 1e-6 * double(++samples_)));
    out->timestamp_ns = now_ns;
    out->sequence = samples_;
    return true;
  }
  void Write(const Wrench& w, std::int64_t, std::uint32_t) override { last_ = w; }
  void EmergencyZero() noexcept override {}
  Wrench last_;
  int reads_ = 0, samples_ = 0;
};

TEST(HapticCycle, ASlowerDeviceIsHeldBetweenItsSamples) {
  EveryTenthRead device;
  HalfspaceContactModel model(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  HapticCycle cycle(device, &model, HapticCycleConfig{.cycle_seconds = 1e-4});
  cycle.Start(0);  // read 0: sample 1
  for (int i = 1; i <= 2000; ++i) {
    const CycleRecord rec = cycle.Step(i * 100'000);
    EXPECT_EQ(rec.new_sample, i % 10 == 0) << "cycle " << i;
    const int newest = 1 + i / 10;  // samples delivered so far
    EXPECT_NEAR(rec.p_WD[2], 0.03 - 1e-6 * newest, 1e-15) << "cycle " << i;
    EXPECT_EQ(rec.device_sequence, std::uint64_t(newest)) << "cycle " << i;
    EXPECT_FALSE(rec.safety_flags & kSafetyDeviceSilent) << "cycle " << i;
  }
  EXPECT_EQ(cycle.safety().stats().device_silent, 0);
}

TEST(ReplayDevice, BadCsvRowsAreReportedWithFileAndLine) {
  testing::TempDir dir;
  const auto file = dir / "bad.csv";
  WriteText(file, "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.1,0,0,0,1,0,0\n");
  ExpectErrorMentions([&] { ReadTrajectoryCsv(file); }, {"bad.csv:3", "8 columns"});
  WriteText(file, "0,0,0,0,1,0,0,0\n0.1,0,zero,0,1,0,0,0\n");
  ExpectErrorMentions([&] { ReadTrajectoryCsv(file); }, {"bad.csv:2", "'zero'"});
  WriteText(file, "0,0,0,0,1,0,0,0\n0,0,0,0,1,0,0,0\n");
  ExpectErrorMentions([&] { ReadTrajectoryCsv(file); }, {"bad.csv:2", "not greater"});
  WriteText(file, "0,0,0,0,0,0,0,0\n");
  ExpectErrorMentions([&] { ReadTrajectoryCsv(file); }, {"bad.csv:1", "quaternion is zero"});
  WriteText(file, "0,0,0,nan,1,0,0,0\n");
  ExpectErrorMentions([&] { ReadTrajectoryCsv(file); }, {"bad.csv:1", "not finite"});
  WriteText(file, "t,x,y,z,qw,qx,qy,qz\n");
  ExpectErrorMentions([&] { ReadTrajectoryCsv(file); }, {"bad.csv", "no samples"});
  ExpectErrorMentions([&] { ReadTrajectoryCsv(dir / "missing.csv"); }, {"missing.csv", "does not exist"});
}

// A plugin library is one of the session's inputs: no output (a --log) may replace it, under
// its own name or through a symlink.
TEST(PluginDevice, ThePluginLibraryIsAnInputNoOutputMayReplace) {
  testing::TempDir dir;
  std::filesystem::copy_file(CONTACTLAB_EXAMPLE_PLUGIN_PATH, dir / "device.so");
  std::filesystem::create_symlink(dir / "device.so", dir / "link.csv");
  InputFileRecord record;
  CheckOutputIsNoRecordedInput(dir / "device.so", "--log");  // not read yet: nothing to refuse
  PluginDevice dev(dir / "device.so", "radius=0.05");
  for (const char* name : {"device.so", "link.csv"}) {
    ExpectErrorMentions([&] { CheckOutputIsNoRecordedInput(dir / name, "--log"); }, {name, "--log", "device.so"});
  }
  CheckOutputIsNoRecordedInput(dir / "log.csv", "--log");
}

TEST(PluginDevice, ExamplePluginLoadsReadsWritesAndZeroes) {
  PluginDevice dev(CONTACTLAB_EXAMPLE_PLUGIN_PATH, "radius=0.05");
  EXPECT_EQ(dev.name(), "example-circle");
  EXPECT_EQ(dev.capabilities().dof_out, 6);
  EXPECT_DOUBLE_EQ(dev.capabilities().max_force, 5.0);
  DeviceState s;
  ASSERT_TRUE(dev.Read(0, &s));
  EXPECT_NEAR(s.X_WD.translation.x(), 0.05, 1e-15);
  ASSERT_TRUE(dev.Read(1000 * kMs, &s));  // a quarter turn later (period 4 s)
  EXPECT_NEAR(s.X_WD.translation.y(), 0.05, 1e-12);
  Wrench w;
  w.force.x() = 1;
  dev.Write(w, 0, 0);
  dev.EmergencyZero();
  EXPECT_EQ(dev.write_errors(), 0);
}

// A plugin sample with quaternion (1e200, 0, 0, 0) was accepted (its norm is inf, which passed
// "> 1e-12") and normalised to (0, 0, 0, 0), so the session's own log would not replay. Such a
// sample, a zero or near-zero one and a non-finite one are now not acted on and counted, as
// the UDP device refuses them; a quaternion that is not unit but usable is normalised.
TEST(PluginDevice, ASampleWhoseQuaternionOverflowsOrVanishesIsNotActedOn) {
  for (const char* bad : {"1e200,0,0,0", "0,1e160,0,0", "0,0,0,0", "1e-7,0,0,0", "nan,0,0,0", "inf,0,0,0"}) {
    SCOPED_TRACE(bad);
    PluginDevice dev(CONTACTLAB_FIXED_SAMPLE_PLUGIN_PATH, bad);
    DeviceState s;
    EXPECT_FALSE(dev.Read(0, &s));
    EXPECT_EQ(dev.read_errors(), 1);
    EXPECT_EQ(s.X_WD.rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());  // the last good pose
  }
  for (const char* good : {"2,0,0,0", "1e150,0,0,0", "0,0.001,0,0"}) {
    SCOPED_TRACE(good);
    PluginDevice dev(CONTACTLAB_FIXED_SAMPLE_PLUGIN_PATH, good);
    DeviceState s;
    ASSERT_TRUE(dev.Read(0, &s));
    EXPECT_NEAR(s.X_WD.rotation.norm(), 1.0, 1e-15);
    EXPECT_EQ(dev.read_errors(), 0);
  }
}

TEST(PluginDevice, LoadFailuresNameTheLibraryAndTheCause) {
  ExpectErrorMentions([] { PluginDevice d("/nonexistent/libnothing.so", ""); }, {"libnothing.so", "not found"});
  ExpectErrorMentions([] { PluginDevice d(CONTACTLAB_EXAMPLE_PLUGIN_PATH, "radius=oops"); },
                      {"libcontactlab_example_device.so", "refused", "radius=oops"});
}

// `--device plugin:FIFO` blocked forever in dlopen, which opens and reads the named file. A
// plugin that is a named pipe, a folder or a device is now refused by name before dlopen. The
// pipe holds a few bytes and has a writer, so that dlopen, if it were reached, would fail at
// once ("file too short") instead of hanging the test.
TEST(PluginDevice, NamedPipeFolderOrDeviceIsRefusedByNameWithoutBlockingInDlopen) {
  testing::TempDir dir;
  const std::filesystem::path fifo = dir / "libfifo.so";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int pipe_fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(pipe_fd, 0);
  ASSERT_EQ(::write(pipe_fd, "not an ELF file", 15), 15);
  ExpectErrorMentions([&] { PluginDevice d(fifo, ""); }, {"libfifo.so", "is a named pipe, not a device plugin library"});
  ExpectErrorMentions([&] { MakeDevice("plugin:" + fifo.string()); }, {"libfifo.so", "is a named pipe"});
  ::close(pipe_fd);
  ExpectErrorMentions([&] { PluginDevice d(dir.path(), ""); }, {"is a folder, not a device plugin library"});
  ExpectErrorMentions([] { PluginDevice d("/dev/zero", ""); }, {"/dev/zero", "is a character device"});
}

TEST(DeviceFactory, MakesEachKindAndRejectsBadSpecs) {
  EXPECT_EQ(MakeDevice("sim")->name(), "sim");
  EXPECT_EQ(MakeDevice("sim:circle:0.02:3")->name(), "sim");
  EXPECT_EQ(MakeDevice("udp:0")->name(), "udp");
  EXPECT_EQ(MakeDevice(std::string("plugin:") + CONTACTLAB_EXAMPLE_PLUGIN_PATH)->name(), "example-circle");
  ExpectErrorMentions([] { MakeDevice("phantom"); }, {"phantom", "unknown device kind"});
  ExpectErrorMentions([] { MakeDevice("udp:70000"); }, {"udp:70000", "0..65535"});
  ExpectErrorMentions([] { MakeDevice("sim:circle:x"); }, {"radius", "'x'"});
  ExpectErrorMentions([] { MakeDevice("replay:/nonexistent/t.csv"); }, {"/nonexistent/t.csv"});
}

// A port is decimal digits: "udp:127.0.0.1:1e3" was read as port 1000 (a number, not a port).
// An allowed peer is a host's address: 0.0.0.0, 255.255.255.255 or a multicast group never send
// a datagram (and the one allowed peer is where wrench packets go), so they are refused naming
// --device-peer.
TEST(DeviceFactory, PortsAreDecimalDigitsAndPeersAreAddressesDatagramsCanComeFrom) {
  for (const char* spec : {"udp:1e3", "udp:127.0.0.1:1e3", "udp:0:1e3", "udp:+80", "udp:0x50", "udp:99999"}) {
    ExpectErrorMentions([&] { MakeDevice(spec); }, {spec, "is not in 0..65535 (decimal digits)"});
  }
  EXPECT_EQ(MakeDevice("udp:00000")->name(), "udp");
  const std::pair<const char*, const char*> not_hosts[] = {{"0.0.0.0", "the unspecified address"},
                                                           {"0.1.2.3", "the unspecified address"},
                                                           {"255.255.255.255", "the broadcast address"},
                                                           {"224.0.0.1", "a multicast address"},
                                                           {"239.255.255.250", "a multicast address"},
                                                           {"240.0.0.1", "a reserved address"}};
  for (const auto& [peer, kind] : not_hosts) {
    ExpectErrorMentions([&] { MakeDevice("udp:0.0.0.0:0", DeviceOptions{{peer}}); }, {"--device-peer", peer, kind});
    UdpDeviceParams p;
    ASSERT_TRUE(ParseIpv4(peer, &p.bind_address));
    p.allowed_peers = {p.bind_address};
    p.bind_address = 0x7f000001;
    ExpectErrorMentions([&] { UdpDevice d(p); }, {"allowed peer", peer, kind});
  }
  // A host's address, on or off the loopback, is an allowed peer.
  EXPECT_EQ(MakeDevice("udp:127.0.0.1:0", DeviceOptions{{"192.168.1.20", "127.0.0.1"}})->name(), "udp");
}

TEST(SpacenavDevice, OpeningWithoutDaemonFailsWithAClearMessage) {
  if (!SpacenavAvailable()) GTEST_SKIP() << "built without libspnav";
  // No spacenavd and no device on the test machine.
  try {
    auto d = MakeDevice("spacenav");
    GTEST_SKIP() << "a spacenavd is running here; nothing to check";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spacenavd"), std::string::npos) << e.what();
  }
}

// A SpaceMouse is input only: it reports no force output (max force 0). A session with it
// must start and run, writing zero force, instead of the safety filter refusing the limits.
// Checked without the hardware: a simulated hand behind the spacenav capabilities.
TEST(SpacenavDevice, InputOnlyDeviceStartsASessionAndWritesZeroForce) {
  const DeviceCapabilities caps = SpacenavDevice::Capabilities(SimDeviceParams::DefaultCapabilities());
  EXPECT_EQ(caps.dof_out, 0);
  EXPECT_EQ(caps.max_force, 0);
  SimDeviceParams params;
  params.capabilities = caps;
  // Down onto the plane z = 0 (box half height 1 cm, target 5 mm below its bottom).
  SimDevice hand(params, [](double t) {
    return Pose::FromTranslation(Eigen::Vector3d(0, 0, t < 0.2 ? 0.03 : 0.005));
  });
  WorkspaceMappedDevice mapped(hand, Pose{});
  HalfspaceContactModel model(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  std::unique_ptr<HapticCycle> cycle;
  ASSERT_NO_THROW(cycle = std::make_unique<HapticCycle>(mapped, &model, HapticCycleConfig{}));
  cycle->Start(0);
  int touching = 0;
  double max_force = 0;
  for (int i = 1; i <= 1500; ++i) {
    const CycleRecord rec = cycle->Step(i * kMs);
    touching += rec.points_in_contact > 0;
    max_force = std::max({max_force, std::abs(rec.device_force[0]), std::abs(rec.device_force[1]),
                          std::abs(rec.device_force[2]), std::abs(rec.device_torque[0]),
                          std::abs(rec.device_torque[1]), std::abs(rec.device_torque[2])});
    EXPECT_FALSE(rec.safety_flags & (kSafetyForceClamped | kSafetyTorqueClamped)) << "cycle " << i;
  }
  EXPECT_GT(touching, 100);  // contact was rendered, only not displayed
  EXPECT_EQ(max_force, 0.0);
  EXPECT_EQ(hand.held_wrench().force.norm(), 0.0);
  EXPECT_EQ(cycle->safety().stats().force_clamped, 0);
}

}  // namespace
}  // namespace contactlab

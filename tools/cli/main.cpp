// SPDX-License-Identifier: MIT
// The `streamclust` command: subcommand dispatch, help texts and exit codes
// (cli/main.hpp).

#include "cli/main.hpp"

#include "cli/cluster.hpp"
#include "cli/evaluate.hpp"
#include "cli/evaluate_objects.hpp"
#include "cli/evaluate_tracks.hpp"
#include "cli/info.hpp"
#include "cli/live.hpp"
#include "cli/replay.hpp"
#ifdef STREAMCLUST_TOOL_ROS2
#include "cli/ros2_node.hpp"
#endif
#include "cli/memory_context.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"

#include <streamclust/io/error.hpp>

#include <algorithm>
#include <exception>
#include <new>

namespace streamclust::cli {

const char* main_help() {
  return R"(streamclust - continuous clustering of LiDAR point streams (C-ARC)

usage: streamclust <command> [options]

commands:
  cluster INPUT   cluster a recorded stream as the sensor delivered it
  live SOURCE     cluster a Livox LiDAR's stream live from the network (livox-sdk2://, livox-sdk1://)
  ros2            a ROS 2 node over DDS: points from a topic in, labelled clouds, boxes and
                  detections out (built with Cyclone DDS)
  replay INPUT --to URL   emulate a Livox LiDAR: send INPUT (or --simulate) as its packets,
                  or as a ROS 2 driver's messages (--to ros2:///livox/lidar)
  info INPUT      format, fields, point count, time span and bounds of an input
  simulate        write a simulated stream with its ground truth
  evaluate        simulate a scenario, cluster it (C-ARC and/or the frame baseline)
                  and score every retrieval against the ground truth
  evaluate --objects   the objects preset against C-ARC, Euclidean clustering and the
                  RANSAC + Euclidean frame pipeline: are the clusters objects?
  evaluate --tracks    the tracker against the objects' truth boxes and velocities and
                  against a centroid Kalman tracker: CLEAR MOT, IDF1, velocity error

Run 'streamclust <command> --help' for the options of a command.
Exit codes: 0 ok, 2 usage error, 3 verification mismatch, 4 input error,
5 out of memory, 6 network error (live, ros2, replay).
)";
}

/// The help of `streamclust cluster`: the presets (cli::preset_summaries),
/// the policies and their options (the tool's registry) and every other option.
std::string cluster_help() {
  std::string text = R"(usage: streamclust cluster INPUT [options]

Streams INPUT point by point through the continuous C-ARC engine, retrieves
clusters at a fixed rate of stream time and writes the results.

input (a point file, or a recording: ROS 1 bag, rosbag2 folder or .db3, MCAP, LVX/LVX2):
  --format auto|csv|pcd|ply|kitti|bag|db3|mcap|lvx   input format (default auto: extension and content)
  --topic NAME                      the recording's point-cloud topic (needed when it has several),
                                    or the LVX file's LiDAR (serial number or device index)
  --time-unit s|ms|us|ns            unit of the time column (default: ns for offset_time, s otherwise)
  --point-rate HZ                   the stream's point rate: records without a time field
                                    get t = index / HZ (a time field is kept)
  --time-origin S                   whole seconds times count from (default: those of the
                                    first time); --poses are read from the same origin
policies (a preset first, then every option below overrides it):
)";
  text += preset_help();
  text += R"(  --window-time SECONDS | --window-count N   sliding window (default 0.1 s)
  --rate HZ                         retrievals per second of stream time (default 20)
  --max-time-jump S                 a point more than S ahead of the stream is rejected as a
                                    time_jump until 256 agree (a pause); default 60
)";
  text += ToolRegistry::help(Slot::linkage);
  text += "  --mask W                          odd mask width in cells (default 5)\n";
  text += ToolRegistry::help(Slot::spatial_index);
  text += ToolRegistry::help(Slot::connectivity, ClusterOptions{}.connectivity);
  text += ToolRegistry::help(Slot::projection);
  text += R"(  --fov-azimuth MIN:MAX  --fov-elevation MIN:MAX (deg)  --fov-z MIN:MAX (m, cylindrical)
  --min-range M                     closer points are rejected (default 0.1)
  --grid auto|HxW                   auto: adaptive resolution on the first window
  --max-multiplicity T_M            adaptive target (default 2; alias --multiplicity)
  --mode continuous|frame           frame: each retrieval clusters its window from scratch
motion and structure removal (continuous mode; the objects presets turn --ground on):
  --poses FILE                      the sensor's poses, a TUM trajectory (t tx ty tz qx qy qz qw,
                                    world from vehicle, on the points' clock), or a recording
                                    (.mcap, .db3, .bag, a rosbag2 folder) with a nav_msgs/Odometry
                                    topic: each point placed in the world at its capture time
  --poses-topic NAME                the recording's odometry topic (default: its only one)
  --mount ROLL,PITCH,YAW            the sensor's rotation [deg] (0,30,0: pitched 30 down; 180,0,0:
                                    upside down); with --poses, on the vehicle
  --ground | --no-ground            class ground, wall and ceiling points out of the clustering
                                    (HeightMapGround); without --mount/--poses and --sensor-height,
                                    the first window's ground plane gives the mount and height
  --sensor-height M                 the sensor's height above the ground under it, (0, 100]
  --ground-tolerance M (default 0.03)   tolerance above the ground bound, [0, 2]
  --ground-cell M (default 0.5)     cell edge of the ground model, (0.05, 10]
  --max-slope DEG (default 15)      steepest ground, [0, 60]
  --no-ceiling                      no ceiling detection
  --no-walls                        no wall detection (walls are then clustered as objects)
)";
  text += R"(outputs:
  --labels FILE     CSV cycle,time,index,label (-1: in the window but unlabelled)
  --cycles all|last|N,M,...         cycles written to --labels, --ply, --pcd (default last)
  --report FILE     JSON: grid and adaptive trace, per-cycle sizes and latencies, totals
                    (cycle latency: wall time of the clusterer's work for the cycle)
  --ply FILE        last selected cycle, coloured by label, with a label property
  --pcd FILE        last selected cycle, with a label field
  --mcap FILE       every cycle for Foxglove: the window as a PointCloud coloured by label
                    and the clusters as boxes (SceneUpdate), at the stream's time
  --tracks FILE     tracked objects every cycle, CSV cycle,time,track_id,cluster_id,x,y,z,vx,vy,vz,
                    length,width,height,yaw,points,state: oriented boxes of the components of
                    10 points or more, followed by a Kalman tracker (world frame of --poses or
                    --mount, else the sensor's; m, m/s, rad; state tentative, confirmed, coasting)
  --png FILE        a bird's-eye picture of the last selected cycle: clusters coloured, boxes,
                    a metre scale
  --png-every N     instead, a picture of every N-th cycle: FILE_000000.png, FILE_0000NN.png, ...
  --verify          compare every retrieval with the batch clusterer; exit 3 on mismatch
  --quiet, -q       no progress bar, no summary line

examples:
  streamclust cluster scan.csv --preset carc-mid360 --labels labels.csv
  streamclust cluster frames.pcd --point-rate 100000 --window-time 0.2 --report report.json
  streamclust cluster scan.csv --preset carc-avia --index overwrite --mode frame --ply out.ply
  streamclust cluster scan.bin --format kitti --point-rate 1200000 --verify
  streamclust cluster run.bag --topic /livox/lidar --preset carc-mid360 --labels labels.csv
  streamclust cluster office.csv --preset objects-mid360 --mount 0,0,0 --sensor-height 1.0
)";
  return text;
}

const char* info_help() {
  return R"(usage: streamclust info INPUT [--format F] [--topic NAME] [--time-unit U] [--point-rate HZ]

Prints the format, fields, point count, bounds and time span of INPUT,
reading it once as a stream. An input without a time field is described
too ("no time field"); --point-rate then gives its times as for cluster.
A recording (bag, rosbag2, MCAP) also lists its topics: type, message count.

  --format auto|csv|pcd|ply|kitti|bag|db3|mcap|lvx   input format (default auto: extension and content)
  --topic NAME                      the recording's point-cloud topic, or the LVX file's LiDAR
  --time-unit s|ms|us|ns            unit of the time column (default: ns for offset_time, s otherwise)
  --point-rate HZ                   the stream's point rate: records without a time field
                                    get t = index / HZ
  --time-origin S                   whole seconds times count from (default: the first time's)

examples:
  streamclust info scan.pcd
  streamclust info scan.bin --format kitti --point-rate 1200000
  streamclust info run.mcap
)";
}

const char* simulate_help() {
  return R"(usage: streamclust simulate --out FILE [--sensor S] [--scene C] [--seconds S] [--seed N]
                            [--speed M/S] [--yaw-rate RAD/S] [--noise M] [--dropout P] [--max-range M]
                            [--burst START:LENGTH --burst-speed M/S --burst-yaw-rate RAD/S]
                            [--mount ROLL,PITCH,YAW] [--trajectory FILE] [--objects FILE]
                            [--objects-rate HZ] [--class-column] [--start-time S]

Writes a simulated point stream with its ground truth to FILE (.csv: columns
x,y,z,intensity,t,label; .pcd: binary with a label field). label is the
instance id of the object hit, 0 for structure (ground, walls, ceiling).
Beside it, the sensor trajectory (TUM, 200 Hz, world from sensor) in
FILE without its extension + .tum, or --trajectory FILE, and every object's
box over time (the trackers' truth; CSV
time,instance,label,moving,x,y,z,vx,vy,vz,length,width,height,yaw: world
frame, box centre [m], velocity [m/s], extent [m], yaw [rad] of the length
axis, moving 0/1; --objects-rate HZ rows per object per second, default 20) in
FILE without its extension + .objects.csv, or --objects FILE.
Points are in the sensor frame at capture time; no-returns are dropped.
Deterministic for a given seed.

  --sensor mid360|mid40|mid70|avia|spinning32   (default mid360; rates 200/100/100/240/576 kHz)
  --scene office|forest|street|hills            (default office)
  --sensor synthetic --scene room               the older built-in stand-in; --point-rate HZ
                                                (default 200000) times it as t = index / HZ
  --seconds S | --duration S (default 1)  --seed N (default 1)
  --speed M/S  --yaw-rate RAD/S                 ego-motion along +x / about +z (default 0)
  --burst START:LENGTH                          from START for LENGTH seconds the sensor moves with
  --burst-speed M/S  --burst-yaw-rate RAD/S     these instead (a burst of fast ego-motion)
  --noise M (default 0.02)  --dropout P (default 0)  --max-range M (default 40)
  --mount ROLL,PITCH,YAW                        the sensor's mount [deg] (pitch > 0 tilts it down,
                                                roll 180 is upside down; default 0,0,0)
  --class-column                                CSV: a class column (0 object, 1 ground, 2 wall, 3 ceiling)
  --start-time S                                whole seconds added to every time written, points,
                                                trajectory and objects (e.g. Unix time 1700000000; default 0)

examples:
  streamclust simulate --sensor mid360 --scene office --seconds 2 --out office.csv
  streamclust simulate --sensor avia --scene forest --speed 1.5 --out forest.pcd
  streamclust simulate --scene forest --burst 1:0.3 --burst-yaw-rate 3 --out burst.csv
)";
}

/// The help of `streamclust evaluate`, the policies from the tool's registry.
std::string evaluate_help() {
  std::string text = R"(usage: streamclust evaluate [scenario options] [method options] [--json FILE] [--series FILE]
       streamclust evaluate --objects [options]   (see streamclust evaluate --objects --help)
       streamclust evaluate --tracks [options]    (see streamclust evaluate --tracks --help)

Simulates a scenario with ground truth, clusters it with C-ARC (the continuous
engine) and/or the frame baseline (Bogoslavskyi & Stachniss: overwrite range
image, re-clustered from scratch on the window), both on the grid the adaptive
loop chooses from the first window, retrieves at --rate Hz of stream time and
scores every retrieval after the first window against the ground truth: ARI on
object points, OSE / USE, panoptic PQ at IoU > 0.5, coverage, object rates
(docs/evaluation-metrics.md). Prints the means; docs/evaluation.md has the study.

scenario (as for simulate):
  --sensor mid360|mid40|mid70|avia|spinning32   (default mid360)
  --scene office|forest|street|hills            (default office)
  --mount ROLL,PITCH,YAW                        the sensor's mount [deg] (default 0,0,0)
  --duration S | --seconds S (default 2)  --seed N (default 1)
  --speed M/S  --yaw-rate RAD/S                 constant ego-motion (default 0)
  --burst START:LENGTH  --burst-speed M/S  --burst-yaw-rate RAD/S
                                                ego-motion burst, then back to --speed/--yaw-rate;
                                                adds the recovery time to the output
  --noise M (default 0.02)  --dropout P (default 0)  --max-range M (default 40)
methods:
  --method carc|baseline|both       (default both)
  --frames sliding|tumbling         baseline: re-cluster the window at every retrieval (default),
                                    or non-overlapping frames of T_B, the last one held in between
)";
  text += ToolRegistry::help(Slot::linkage);
  text += R"(  --mask W                          odd mask width (default 3, the paper's comparison)
  --window-time T_B                 sliding window / frame length [s] (default 0.1)
  --rate HZ                         retrievals per second of stream time (default 20)
  --multiplicity T_M                adaptive-loop target (default 2; the paper's fine grid: 1.25)
  --grid auto|HxW                   a given grid instead of the adaptive loop's
  C-ARC's grid (not overwrite: the baseline's) and components (same scores):
)";
  text += ToolRegistry::help(Slot::spatial_index);
  text += ToolRegistry::help(Slot::connectivity, ClusterOptions{}.connectivity);
  text += R"(  --fov-azimuth MIN:MAX  --fov-elevation MIN:MAX   (default: the sensor's FOV)
  --min-range M                     (default 0.1)
  --structure keep|drop             drop: remove the ground-truth structure points (ground, walls)
                                    before clustering, an oracle ground/wall removal (default keep)
  --min-points N                    objects / segments smaller than N points are not
                                    counted as FN / FP or rated (default 10)
outputs:
  --json FILE       scenario, policy, grid, per method the means, the recovery and every retrieval
  --series FILE     CSV, one row per method and retrieval: method,time,window,<metrics>
  --quiet, -q       no table

examples:
  streamclust evaluate --sensor mid360 --scene forest --multiplicity 1.25
  streamclust evaluate --sensor avia --scene office --theta 80 --json avia.json
  streamclust evaluate --sensor mid70 --scene street --linkage euclidean --distance 0.3
  streamclust evaluate --scene forest --duration 2.5 --burst 1:0.3 --burst-yaw-rate 3 --series burst.csv
)";
  return text;
}

/// The message on `err` and the exit code of the exception being handled
/// by `command` (call it only inside a catch block).
int report_exception(const std::string& command, std::ostream& err) {
  try {
    throw;
  } catch (const UsageError& e) {
    err << "streamclust: " << e.what() << "\n";
    return kUsage;
  } catch (const io::InputError& e) {
    err << "streamclust: input error: " << e.what() << "\n";
    return kInputError;
  } catch (const OutOfMemory& e) {
    err << "streamclust: " << e.what() << "\n";
    return kOutOfMemory;
  } catch (const NetworkError& e) {
    err << "streamclust: network error: " << e.what() << "\n";
    return kNetworkError;
  } catch (const std::bad_alloc&) {
    err << "streamclust: " << (command.empty() ? std::string("streamclust") : command) << ": out of memory\n";
    return kOutOfMemory;
  } catch (const std::exception& e) {
    err << "streamclust: error: " << e.what() << "\n";
    return kInputError;
  }
}

/// Runs the command line; returns the process exit code.
int run_main(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const std::string command = args.empty() ? std::string() : args[0];
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      (args.empty() ? err : out) << main_help();
      return args.empty() ? kUsage : kOk;
    }
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    const bool help = std::find(rest.begin(), rest.end(), "--help") != rest.end() ||
                      std::find(rest.begin(), rest.end(), "-h") != rest.end();
    if (command == "cluster") {
      if (help) {
        out << cluster_help();
        return kOk;
      }
      return run_cluster(parse_cluster_options(rest), out, err);
    }
    if (command == "live") {
      if (help) {
        out << live_help();
        return kOk;
      }
      return run_live(parse_live_options(rest), out, err);
    }
    if (command == "ros2") {
#ifdef STREAMCLUST_TOOL_ROS2
      if (help) {
        out << ros2_help();
        return kOk;
      }
      return run_ros2(parse_ros2_options(rest), out, err);
#else
      throw UsageError("ros2: this streamclust was built without ROS 2 support (it needs Cyclone DDS: "
                       "apt-get install cyclonedds-dev, then build again)");
#endif
    }
    if (command == "replay") {
      if (help) {
        out << replay_help();
        return kOk;
      }
      return run_replay(parse_replay_options(rest), out, err);
    }
    if (command == "info") {
      if (help) {
        out << info_help();
        return kOk;
      }
      return run_info(parse_info_options(rest), out);
    }
    if (command == "simulate") {
      if (help) {
        out << simulate_help();
        return kOk;
      }
      return run_simulate(parse_simulate_options(rest), out);
    }
    if (command == "evaluate") {
      const auto tracks = std::find(rest.begin(), rest.end(), "--tracks");
      if (tracks != rest.end()) {
        if (help) {
          out << evaluate_tracks_help();
          return kOk;
        }
        std::vector<std::string> options(rest.begin(), tracks);
        options.insert(options.end(), tracks + 1, rest.end());
        return run_evaluate_tracks(parse_evaluate_tracks_options(options), out);
      }
      const auto objects = std::find(rest.begin(), rest.end(), "--objects");
      if (objects != rest.end()) {
        if (help) {
          out << evaluate_objects_help();
          return kOk;
        }
        std::vector<std::string> options(rest.begin(), objects);
        options.insert(options.end(), objects + 1, rest.end());
        return run_evaluate_objects(parse_evaluate_objects_options(options), out, err);
      }
      if (help) {
        out << evaluate_help();
        return kOk;
      }
      return run_evaluate(parse_evaluate_options(rest), out);
    }
    throw UsageError("unknown command '" + command + "' (expected cluster, live, ros2, replay, info, simulate or evaluate)");
  } catch (...) {
    return report_exception(command, err);
  }
}

}  // namespace streamclust::cli

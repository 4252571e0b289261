"""What the Python layer adds to a render, and what `import grtrace` costs: the same requests through grtrace.render
and through the C++ front door (tests/benchmarks/app_benchmark: app::render), alternated in one run, and the import
timed in fresh interpreters. Prints one line of JSON per measurement.

    PYTHONPATH=<site of the installed module> python3 python/benchmarks/render_overhead.py BUILD/tests/benchmarks/app_benchmark

Run it on a build with optimisation (the release or bench preset): the ci preset's benchmarks are compiled at -O0.
"""

import json
import statistics
import subprocess
import sys
import time

import grtrace

REQUESTS = {
    "kerr_disk": dict(metric="kerr", spin=0.9, scene="disk", camera_r=50, camera_theta=80, fov=30, width=256,
                      height=256),
    "main_frame": dict(width=256, height=256),
}


def python_seconds(options, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        grtrace.render(**options)
        times.append(time.perf_counter() - t0)
    return times


def cpp_seconds(binary, name, min_time):
    out = subprocess.run([binary, f"--benchmark_filter=front_door/{name}/", f"--benchmark_min_time={min_time}",
                          "--benchmark_format=json"], capture_output=True, text=True, check=True).stdout
    run = json.loads(out)["benchmarks"][0]
    return run["real_time"] / 1e3  # milliseconds -> seconds


def import_seconds(repeats=7):
    def fresh(code):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        return time.perf_counter() - t0

    bare = min(fresh("pass") for _ in range(repeats))
    full = min(fresh("import grtrace") for _ in range(repeats))
    return full - bare, full


def main():
    binary = sys.argv[1]
    for name, options in REQUESTS.items():
        python_seconds(options, 3)  # warm up both sides
        cpp_seconds(binary, name, 0.5)
        py, cpp = [], []
        for _ in range(4):  # alternated
            py.append(statistics.median(python_seconds(options, 10)))
            cpp.append(cpp_seconds(binary, name, 2))
        p, c = statistics.median(py), statistics.median(cpp)
        print(json.dumps({"request": name, "python_ms": round(p * 1e3, 3), "cpp_ms": round(c * 1e3, 3),
                          "difference_ms": round((p - c) * 1e3, 3), "ratio": round(p / c, 4),
                          "python_runs_ms": [round(v * 1e3, 2) for v in py],
                          "cpp_runs_ms": [round(v * 1e3, 2) for v in cpp]}))
    extra, whole = import_seconds()
    print(json.dumps({"import_grtrace_s": round(extra, 4), "python_with_import_s": round(whole, 4)}))


if __name__ == "__main__":
    main()

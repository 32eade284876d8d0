"""The Dask driver beside the one-process run on the same city, in one run: both times, their
ratio, whether the files are the same, and the 10^6-tree estimate from the measured tasks.

    sylva city-demo -o trees.csv --trees 3000 --region PacfNW
    python bench_dask.py trees.csv
"""
import hashlib, os, shutil, time, sys
def digest(d):
    return {os.path.relpath(os.path.join(r, f), d): hashlib.sha256(open(os.path.join(r, f), "rb").read()).hexdigest()
            for r, _, fs in os.walk(d) for f in fs}
if __name__ == "__main__":
    import sylva, sylva.dask
    from distributed import Client, LocalCluster
    csv = sys.argv[1]
    for d in ("cmp-one", "cmp-dask"): shutil.rmtree(d, ignore_errors=True)
    t = time.perf_counter(); sylva.city(csv, "cmp-one", years=[0, 10, 20, 30]); one = time.perf_counter() - t
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as c, Client(c) as cl:
        t = time.perf_counter(); s = sylva.dask.city(csv, "cmp-dask", client=cl, years=[0, 10, 20, 30]); dk = time.perf_counter() - t
    a, b = digest("cmp-one"), digest("cmp-dask")
    print(f"one process (rayon, 2 threads): {one:.1f} s; Dask 2 workers: {dk:.1f} s; ratio {dk/one:.2f}; files {len(a)} identical {a == b}")
    g = s["task_seconds"]["growth"]
    print(f"growth tasks {len(g)} sum {sum(g):.1f} s max {max(g):.1f} s; tile tasks {len(s['task_seconds']['tiles'])} sum {sum(s['task_seconds']['tiles']):.2f} s")
    for w in (2, 8, 32):
        e = sylva.dask.estimate(s, trees=1_000_000, epochs=4, workers=w)
        print(w, {k: round(v, 1) for k, v in e.items()})

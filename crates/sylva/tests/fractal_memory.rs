//! The thesis' point about fractal trees: generation needs memory for the rules, not for the
//! tree. Heap use is measured with a counting allocator while trees of different depths stream
//! into a vector file, an SVG and a PNG drawing, counting only the measuring thread's
//! allocations. (One test in this binary, so that no other test runs beside it.)

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicIsize, Ordering::Relaxed};
use sylva::drawing::{DrawOptions, VecWriter, View, draw_png, write_svg};
use sylva::nagel::FractalParams;

struct Counting;

static NOW: AtomicIsize = AtomicIsize::new(0);
static PEAK: AtomicIsize = AtomicIsize::new(0);

thread_local! {
    /// Whether this thread's allocations are being counted. Only the measuring thread's are:
    /// the test harness's own thread allocates now and then while a test runs, and on a busy
    /// machine that landed inside the window. (A const-initialised `Cell` needs no allocation
    /// and no destructor, so the allocator may read it at any time.)
    static COUNTED: Cell<bool> = const { Cell::new(false) };
}

fn counted() -> bool {
    COUNTED.try_with(Cell::get).unwrap_or(false)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if counted() {
            let size = layout.size() as isize;
            PEAK.fetch_max(NOW.fetch_add(size, Relaxed) + size, Relaxed);
        }
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if counted() {
            NOW.fetch_sub(layout.size() as isize, Relaxed);
        }
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Heap bytes `f` needed, on this thread, above what was in use when it started.
fn peak_of(f: impl FnOnce()) -> usize {
    NOW.store(0, Relaxed);
    PEAK.store(0, Relaxed);
    COUNTED.set(true);
    f();
    COUNTED.set(false);
    PEAK.load(Relaxed).max(0) as usize
}

fn tree(depth: u32) -> sylva::nagel::fractal::Fractal {
    FractalParams {
        depth,
        angle_variation: 8.0,
        length_variation: 0.1,
        max_segments: u64::MAX,
        ..Default::default()
    }
    .build()
    .unwrap()
}

#[test]
fn streaming_memory_does_not_grow_with_depth() {
    let (shallow, deep) = (tree(6), tree(18));
    let mut segments = [0u64; 2];

    // Vector file: the generator and the writer allocate nothing at all.
    let vec_file = |t: &sylva::nagel::fractal::Fractal, count: &mut u64| {
        peak_of(|| {
            let mut w = VecWriter::new(std::io::sink());
            use sylva::drawing::LineSource;
            t.lines(&mut |a, b, s| {
                *count += 1;
                sylva::drawing::LineSink::segment(&mut w, a, b, s)
            });
            w.finish().unwrap();
        })
    };
    let (v6, v18) = (
        vec_file(&shallow, &mut segments[0]),
        vec_file(&deep, &mut segments[1]),
    );
    assert_eq!(segments, [127, 524_287]);
    assert_eq!(v6, 0, "streaming a vector file allocated {v6} bytes");
    assert_eq!(v18, 0, "streaming a vector file allocated {v18} bytes");

    // SVG: a few fixed buffers, the same for 127 segments as for half a million.
    let options = DrawOptions {
        view: View::Perspective,
        width: 256,
        height: 256,
        ..Default::default()
    };
    let svg = |t| {
        peak_of(|| {
            write_svg(t, &options, std::io::sink()).unwrap();
        })
    };
    let (s6, s18) = (svg(&shallow), svg(&deep));
    assert!(
        s18 <= s6 + 1024,
        "SVG: {s6} bytes at depth 6, {s18} at depth 18"
    );

    // PNG: the page and one stroke batch (at most 2000 segments) at a time.
    let png = |t| peak_of(|| drop(draw_png(t, &options)));
    let (p12, p18) = (png(&tree(12)), png(&deep));
    let page = 256 * 256 * 4;
    assert!(p18 < 4 * page + 2_000_000, "PNG: {p18} bytes at depth 18");
    assert!(
        (p18 as f64) < 1.25 * p12 as f64,
        "PNG: {p12} bytes at depth 12, {p18} at 18"
    );

    // The meter works: holding the tree costs memory in proportion to it.
    let (m6, m18) = (
        peak_of(|| drop(shallow.skeleton())),
        peak_of(|| drop(deep.skeleton())),
    );
    assert!(
        m18 > 2000 * m6 / 2,
        "skeleton: {m6} bytes at depth 6, {m18} at 18"
    );
    assert!(m18 > 20_000_000);
    eprintln!(
        "peak heap, depth 6 / 18: vec {v6} / {v18} B, svg {s6} / {s18} B, skeleton {m6} / {m18} B; \
         png depth 12 / 18: {p12} / {p18} B"
    );
}

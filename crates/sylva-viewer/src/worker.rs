//! Background generation: the UI sends requests, a thread builds trees, the newest request
//! wins, and the UI never waits.

use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::thread::JoinHandle;
use std::time::Instant;
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree};
use sylva::{GenerateOptions, SkeletonStats, TreeParams};

/// What to build.
pub struct Request {
    pub id: u64,
    pub params: TreeParams,
    pub options: GenerateOptions,
    pub mesh: MeshOptions,
}

/// What came out.
pub struct Built {
    pub id: u64,
    pub mesh: TreeMesh,
    pub stats: SkeletonStats,
    pub generate_ms: f64,
    pub mesh_ms: f64,
}

pub struct Worker {
    requests: Option<Sender<Request>>,
    results: Receiver<Result<Built, String>>,
    thread: Option<JoinHandle<()>>,
    next_id: u64,
    /// Id of the newest request sent, and of the newest result received.
    pub sent: u64,
    pub received: u64,
}

impl Worker {
    /// Starts the thread; `wake` is called after each result (to repaint the UI).
    pub fn start(wake: impl Fn() + Send + 'static) -> Self {
        let (tx, rx) = channel::<Request>();
        let (done_tx, done_rx) = channel();
        let thread = std::thread::Builder::new()
            .name("sylva-generate".into())
            .spawn(move || {
                while let Ok(mut request) = rx.recv() {
                    // Skip to the newest request: older ones are already out of date.
                    loop {
                        match rx.try_recv() {
                            Ok(newer) => request = newer,
                            Err(TryRecvError::Empty) => break,
                            Err(TryRecvError::Disconnected) => return,
                        }
                    }
                    let t = Instant::now();
                    let result = sylva::generate(&request.params, &request.options)
                        .map_err(|e| e.to_string())
                        .map(|skeleton| {
                            let generate_ms = t.elapsed().as_secs_f64() * 1e3;
                            let t = Instant::now();
                            let mesh = mesh_tree(&skeleton, &request.mesh);
                            Built {
                                id: request.id,
                                mesh,
                                stats: skeleton.stats(),
                                generate_ms,
                                mesh_ms: t.elapsed().as_secs_f64() * 1e3,
                            }
                        });
                    if done_tx.send(result).is_err() {
                        return;
                    }
                    wake();
                }
            })
            .expect("spawn the generation thread");
        Self {
            requests: Some(tx),
            results: done_rx,
            thread: Some(thread),
            next_id: 0,
            sent: 0,
            received: 0,
        }
    }

    /// Queues a tree to build.
    pub fn request(&mut self, params: TreeParams, options: GenerateOptions, mesh: MeshOptions) {
        self.next_id += 1;
        self.sent = self.next_id;
        if let Some(tx) = &self.requests {
            let _ = tx.send(Request {
                id: self.next_id,
                params,
                options,
                mesh,
            });
        }
    }

    /// True while a request is being built or waits.
    pub fn busy(&self) -> bool {
        self.received < self.sent
    }

    /// The newest finished result, if any arrived since the last call.
    pub fn poll(&mut self) -> Option<Result<Built, String>> {
        let mut newest = None;
        while let Ok(r) = self.results.try_recv() {
            if let Ok(b) = &r {
                self.received = self.received.max(b.id);
            } else {
                self.received = self.sent;
            }
            newest = Some(r);
        }
        newest
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.requests.take();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

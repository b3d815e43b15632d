//! Starting and stopping the lab: the listener, the access guard, the run worker.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::sync::Arc;
use std::thread::JoinHandle;

use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::inputs::check_threads;
use tokio::sync::watch;

use crate::api::{AppState, router};
use crate::runs::Runs;
use crate::security::{Access, guard, random_token};
use crate::start::StartConfig;
use crate::studies::Studies;

/// How to start a lab.
#[derive(Debug, Clone)]
pub struct LabOptions {
    /// Everything the lab writes goes under it (created if missing).
    pub dir: PathBuf,
    /// TCP port; 0 picks a free one.
    pub port: u16,
    /// Interface to listen on; default 127.0.0.1 (this machine only).
    pub bind: IpAddr,
    /// Threads of a run (as `fuzzymotiv run --threads`: 1 to
    /// [`MAX_THREADS`](fuzzymotiv_pipeline::files::inputs::MAX_THREADS)); default all cores.
    pub threads: Option<usize>,
    /// The access token; default a new random one (so a restart shuts out open pages).
    pub token: Option<String>,
    /// A config file the page opens on (its motivations, rooms and the settings the lab's
    /// form has), read and checked at start as `fuzzymotiv run` reads it.
    pub config: Option<PathBuf>,
    /// The folder of study files the Studies panel lists (default `studies`, the repository's
    /// when the lab starts at its root); a pasted study's configs are relative to the working
    /// directory.
    pub studies: PathBuf,
}

impl LabOptions {
    /// Loopback, port 8765, all cores.
    pub fn new(dir: PathBuf) -> Self {
        Self {
            dir,
            port: 8765,
            bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
            threads: None,
            token: None,
            config: None,
            studies: PathBuf::from("studies"),
        }
    }
}

/// A running lab.
pub struct Lab {
    addr: SocketAddr,
    token: String,
    dir: PathBuf,
    runtime: tokio::runtime::Runtime,
    closing: watch::Sender<bool>,
    runs: Arc<Runs>,
    studies: Arc<Studies>,
    worker: Option<JoinHandle<()>>,
    server: Option<tokio::task::JoinHandle<()>>,
}

fn io(what: &str, e: impl std::fmt::Display) -> CliError {
    CliError::io(format!("{what}: {e}"))
}

/// The `Host` values the lab answers to.
fn hosts(addr: SocketAddr) -> Vec<String> {
    let port = addr.port();
    let mut hosts = vec![addr.to_string()];
    if addr.ip().is_loopback() || addr.ip().is_unspecified() {
        hosts.extend([
            format!("127.0.0.1:{port}"),
            format!("localhost:{port}"),
            format!("[::1]:{port}"),
        ]);
    }
    hosts.dedup();
    hosts
}

/// The lab's directory `--dir`, created if missing, as an absolute path; a file there is
/// refused.
fn open_dir(dir: &std::path::Path) -> Result<PathBuf, CliError> {
    if dir.exists() && !dir.is_dir() {
        return Err(CliError::input(format!(
            "--dir {}: is not a directory; give the lab's directory (created if missing)",
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir).map_err(|e| io(&dir.display().to_string(), e))?;
    dir.canonicalize()
        .map_err(|e| io(&dir.display().to_string(), e))
}

/// The listening socket of `--bind` and `--port`; an address in use or not this machine's is
/// the user's to change (exit 2), with what to do.
fn bind(opts: &LabOptions) -> Result<std::net::TcpListener, CliError> {
    use std::io::ErrorKind;
    let at = format!("--bind {} --port {}", opts.bind, opts.port);
    std::net::TcpListener::bind((opts.bind, opts.port)).map_err(|e| match e.kind() {
        ErrorKind::AddrInUse => CliError::input(format!(
            "{at}: the port is in use (another lab or program listens there); choose another \
             --port, or --port 0 for any free one"
        )),
        ErrorKind::AddrNotAvailable => CliError::input(format!(
            "{at}: {} is not an address of this machine; give one of its interfaces' addresses, \
             127.0.0.1 (this machine only) or 0.0.0.0 (every interface)",
            opts.bind
        )),
        ErrorKind::PermissionDenied => CliError::input(format!(
            "{at}: not allowed to listen there (ports below 1024 need privileges); choose \
             another --port"
        )),
        _ => io(&at, e),
    })
}

impl Lab {
    /// Binds, starts the server and the run worker, and returns once it listens.
    pub fn start(opts: LabOptions) -> Result<Lab, CliError> {
        if let Some(n) = opts.threads {
            check_threads(n as i128).map_err(|m| CliError::input(format!("--threads {m}")))?;
        }
        // The config before anything listens or is written: a bad one leaves nothing behind.
        let start = opts.config.as_deref().map(StartConfig::load).transpose()?;
        let config_rooms = start.as_ref().map(StartConfig::room_files);
        // Bound first: a busy port leaves no directory behind.
        let listener = bind(&opts)?;
        let dir = open_dir(&opts.dir)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(opts.threads.unwrap_or(0))
            .thread_name(|i| format!("lab-run-{i}"))
            .build()
            .map_err(|e| CliError::input(format!("--threads: {e}")))?;
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .map_err(|e| io("the async runtime", e))?;
        listener
            .set_nonblocking(true)
            .map_err(|e| io("listener", e))?;
        let addr = listener.local_addr().map_err(|e| io("listener", e))?;
        let token = match opts.token {
            Some(t) => t,
            None => random_token().map_err(|e| io("the access token", e))?,
        };
        let access = Arc::new(Access {
            token: token.clone(),
            hosts: hosts(addr),
            any_ip_port: addr.ip().is_unspecified().then_some(addr.port()),
            cookie: format!("fuzzymotiv_lab_{}", addr.port()),
        });
        let runs = Arc::new(Runs::open(&dir, config_rooms.unwrap_or_default()));
        let studies = Arc::new(Studies::new(&dir, opts.studies.clone(), opts.threads));
        let (closing, closed) = watch::channel(false);
        let state = Arc::new(AppState {
            dir: dir.clone(),
            runs: runs.clone(),
            studies: studies.clone(),
            start,
            closing: closed.clone(),
        });
        let app = router(state).layer(axum::middleware::from_fn_with_state(access, guard));
        let worker_runs = runs.clone();
        let worker = std::thread::Builder::new()
            .name("lab-worker".into())
            .spawn(move || worker_runs.work(&pool))
            .map_err(|e| io("the run worker", e))?;
        let server = runtime.block_on(async move {
            let listener = tokio::net::TcpListener::from_std(listener)?;
            let mut stop = closed;
            let serve = axum::serve(listener, app).with_graceful_shutdown(async move {
                let _ = stop.wait_for(|c| *c).await;
            });
            Ok::<_, std::io::Error>(tokio::spawn(async move {
                let _ = serve.await;
            }))
        });
        let server = server.map_err(|e| io("listener", e))?;
        Ok(Lab {
            addr,
            token,
            dir,
            runtime,
            closing,
            runs,
            studies,
            worker: Some(worker),
            server: Some(server),
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The access token.
    pub fn token(&self) -> &str {
        &self.token
    }

    /// The lab's directory (absolute).
    pub fn dir(&self) -> &std::path::Path {
        &self.dir
    }

    /// The address to open, with the token.
    pub fn url(&self) -> String {
        // Bound to every interface: this machine reaches it on loopback.
        let host = if self.addr.ip().is_unspecified() {
            format!("127.0.0.1:{}", self.addr.port())
        } else {
            self.addr.to_string()
        };
        format!("http://{host}/?token={}", self.token)
    }

    /// Serves until Ctrl-C, then stops (runs cancelled).
    pub fn wait_for_ctrl_c(self) {
        let _ = self.runtime.block_on(tokio::signal::ctrl_c());
        self.stop();
    }

    /// Stops: cancels every run and study (a running one after its generation), closes the event
    /// streams and the server, and waits for the worker.
    pub fn stop(mut self) {
        self.shutdown();
    }

    fn shutdown(&mut self) {
        let _ = self.closing.send(true);
        self.runs.close();
        self.studies.close();
        if let Some(server) = self.server.take() {
            let _ = self.runtime.block_on(server);
        }
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
    }
}

impl Drop for Lab {
    fn drop(&mut self) {
        self.shutdown();
    }
}

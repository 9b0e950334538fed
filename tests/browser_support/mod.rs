//! A headless Chromium driven through the Chrome DevTools protocol, for the tests of the
//! plan page: the distribution's `chromium` (Debian's package, which `./dev test` installs
//! through `scripts/ensure-lavapipe.sh --tests`), spoken to over `--remote-debugging-pipe`
//! (JSON messages ending in a NUL byte on the browser's file descriptors 3 and 4), so no
//! websocket, port or crate beyond serde_json is involved.
//!
//! A missing browser is an error naming the package, which the tests turn into a failure:
//! they never skip.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use serde_json::{json, Value};
use tempfile::TempDir;

/// How long one protocol call, or a page load, may take before the test fails.
const TIMEOUT: Duration = Duration::from_secs(60);

/// The flags that run Chromium headless here: no sandbox (tests run as root in CI), no
/// GPU, and nothing that reaches the network on its own.
const FLAGS: &[&str] = &[
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-debugging-pipe",
];

/// The browser to run: `$RGRAPH_CHROMIUM`, else `chromium` or `chromium-browser` on PATH.
pub fn find_chromium() -> Result<PathBuf, String> {
    if let Some(path) = std::env::var_os("RGRAPH_CHROMIUM") {
        return Ok(PathBuf::from(path));
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .flat_map(|dir| ["chromium", "chromium-browser"].map(|name| dir.join(name)))
        .find(|candidate| candidate.is_file())
        .ok_or_else(|| {
            missing("no chromium or chromium-browser on PATH, and RGRAPH_CHROMIUM is not set")
        })
}

fn missing(what: &str) -> String {
    format!(
        "the plan page's browser tests need Chromium: {what}. Install Debian's chromium \
         package (`./dev test` does, through scripts/ensure-lavapipe.sh --tests; or run \
         `apt-get install chromium`), or set RGRAPH_CHROMIUM to a Chromium binary"
    )
}

pub struct Browser {
    child: Child,
    to_browser: ChildStdin,
    from_browser: Receiver<Result<Value, String>>,
    /// Events received while waiting for answers, oldest first.
    events: VecDeque<Value>,
    next_id: u64,
    profile: TempDir,
}

impl Browser {
    /// Starts `chromium` headless with a fresh profile.
    pub fn launch(chromium: &Path) -> Result<Browser, String> {
        if !chromium.is_file() {
            return Err(missing(&format!("{} does not exist", chromium.display())));
        }
        let profile = tempfile::tempdir().map_err(|e| format!("a temporary profile: {e}"))?;
        let log = std::fs::File::create(profile.path().join("stderr.log"))
            .map_err(|e| format!("the browser's log: {e}"))?;
        // The shell hands the browser our pipes as its descriptors 3 (commands) and 4
        // (answers and events), the ones --remote-debugging-pipe talks on.
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" 3<&0 4>&1 0</dev/null 1>/dev/null"#)
            .arg(chromium)
            .args(FLAGS)
            .arg(format!(
                "--user-data-dir={}",
                profile.path().join("profile").display()
            ))
            .arg("about:blank")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(log)
            .spawn()
            .map_err(|e| missing(&format!("{} does not start: {e}", chromium.display())))?;
        let to_browser = child.stdin.take().expect("stdin was piped");
        let stdout = child.stdout.take().expect("stdout was piped");
        let (send, from_browser) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            loop {
                let mut message = Vec::new();
                let result = match reader.read_until(0, &mut message) {
                    Ok(0) => Err("the browser closed its pipe (it exited)".to_owned()),
                    Ok(_) => {
                        message.pop();
                        serde_json::from_slice(&message).map_err(|e| format!("bad message: {e}"))
                    }
                    Err(e) => Err(format!("reading from the browser: {e}")),
                };
                let stop = result.is_err();
                if send.send(result).is_err() || stop {
                    return;
                }
            }
        });
        let mut browser = Browser {
            child,
            to_browser,
            from_browser,
            events: VecDeque::new(),
            next_id: 1,
            profile,
        };
        browser.call(None, "Browser.getVersion", json!({}))?;
        Ok(browser)
    }

    /// The browser's stderr so far, for a failure's message.
    pub fn log(&self) -> String {
        std::fs::read_to_string(self.profile.path().join("stderr.log")).unwrap_or_default()
    }

    /// Calls `method` in `session` (a page's) or on the browser, and returns its result.
    pub fn call(
        &mut self,
        session: Option<&str>,
        method: &str,
        params: Value,
    ) -> Result<Value, String> {
        let id = self.next_id;
        self.next_id += 1;
        let mut message = json!({ "id": id, "method": method, "params": params });
        if let Some(session) = session {
            message["sessionId"] = json!(session);
        }
        let mut bytes = serde_json::to_vec(&message).expect("a message serializes");
        bytes.push(0);
        self.to_browser
            .write_all(&bytes)
            .and_then(|_| self.to_browser.flush())
            .map_err(|e| format!("{method}: writing to the browser: {e}"))?;
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let message = self.receive(deadline, method)?;
            if message["id"] == json!(id) {
                if let Some(error) = message.get("error") {
                    return Err(format!("{method} failed: {error}"));
                }
                return Ok(message["result"].clone());
            }
            self.events.push_back(message);
        }
    }

    fn receive(&mut self, deadline: Instant, waiting_for: &str) -> Result<Value, String> {
        let left = deadline.saturating_duration_since(Instant::now());
        match self.from_browser.recv_timeout(left) {
            Ok(message) => message.map_err(|e| format!("{waiting_for}: {e}\n{}", self.log())),
            Err(RecvTimeoutError::Timeout) => Err(format!(
                "{waiting_for}: no answer from the browser in {TIMEOUT:?}\n{}",
                self.log()
            )),
            Err(RecvTimeoutError::Disconnected) => Err(format!(
                "{waiting_for}: the browser is gone\n{}",
                self.log()
            )),
        }
    }

    /// Waits for the event `method` of `session`, keeping the others.
    pub fn wait_for(&mut self, session: &str, method: &str) -> Result<Value, String> {
        let matches = |e: &Value| e["method"] == json!(method) && e["sessionId"] == json!(session);
        if let Some(i) = self.events.iter().position(matches) {
            return Ok(self.events.remove(i).expect("found"));
        }
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let message = self.receive(deadline, method)?;
            if matches(&message) {
                return Ok(message);
            }
            self.events.push_back(message);
        }
    }

    /// Every event received so far, oldest first, leaving none.
    pub fn take_events(&mut self) -> Vec<Value> {
        self.events.drain(..).collect()
    }

    /// A new tab of `width` × `height` CSS pixels, with console messages, exceptions,
    /// log entries (CSP violations, failed loads) and network requests reported.
    pub fn tab(&mut self, width: u32, height: u32) -> Result<Tab, String> {
        let target = self.call(None, "Target.createTarget", json!({ "url": "about:blank" }))?;
        let attached = self.call(
            None,
            "Target.attachToTarget",
            json!({ "targetId": target["targetId"], "flatten": true }),
        )?;
        let session = attached["sessionId"]
            .as_str()
            .ok_or("attachToTarget gave no session")?
            .to_owned();
        for method in [
            "Page.enable",
            "Runtime.enable",
            "Log.enable",
            "Network.enable",
        ] {
            self.call(Some(&session), method, json!({}))?;
        }
        let metrics = json!({
            "width": width, "height": height, "deviceScaleFactor": 1, "mobile": false
        });
        self.call(
            Some(&session),
            "Emulation.setDeviceMetricsOverride",
            metrics,
        )?;
        Ok(Tab { session })
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.call(None, "Browser.close", json!({}));
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// One page of the browser.
pub struct Tab {
    pub session: String,
}

impl Tab {
    /// Opens `path` and waits until it has loaded.
    pub fn open(&self, browser: &mut Browser, path: &Path) -> Result<(), String> {
        let url = format!("file://{}", path.display());
        let navigated =
            browser.call(Some(&self.session), "Page.navigate", json!({ "url": url }))?;
        if let Some(error) = navigated.get("errorText") {
            return Err(format!("opening {url}: {error}"));
        }
        browser.wait_for(&self.session, "Page.loadEventFired")?;
        Ok(())
    }

    /// The value of the JavaScript `expression` in the page (awaited when a promise).
    pub fn eval(&self, browser: &mut Browser, expression: &str) -> Result<Value, String> {
        let result = browser.call(
            Some(&self.session),
            "Runtime.evaluate",
            json!({ "expression": expression, "returnByValue": true, "awaitPromise": true }),
        )?;
        if let Some(exception) = result.get("exceptionDetails") {
            return Err(format!("{expression}\nthrew {exception}"));
        }
        Ok(result["result"]["value"].clone())
    }

    /// Moves the mouse to (`x`, `y`) in CSS pixels of the viewport.
    pub fn hover(&self, browser: &mut Browser, x: f64, y: f64) -> Result<(), String> {
        let event = json!({ "type": "mouseMoved", "x": x, "y": y });
        browser.call(Some(&self.session), "Input.dispatchMouseEvent", event)?;
        Ok(())
    }

    /// Clicks the left button at (`x`, `y`).
    pub fn click(&self, browser: &mut Browser, x: f64, y: f64) -> Result<(), String> {
        for kind in ["mousePressed", "mouseReleased"] {
            let event = json!({ "type": kind, "x": x, "y": y, "button": "left", "clickCount": 1 });
            browser.call(Some(&self.session), "Input.dispatchMouseEvent", event)?;
        }
        Ok(())
    }

    /// Presses and releases `key` ("Tab", "Escape", "Enter"), with Shift when `shift`.
    pub fn press(&self, browser: &mut Browser, key: &str, shift: bool) -> Result<(), String> {
        // Enter types a character, which is what activates a focused button.
        let (code, text) = match key {
            "Tab" => (9, ""),
            "Enter" => (13, "\r"),
            "Escape" => (27, ""),
            other => return Err(format!("no key code for {other}")),
        };
        for kind in ["keyDown", "keyUp"] {
            let event = json!({
                "type": kind, "key": key, "code": key, "text": if kind == "keyDown" { text } else { "" },
                "windowsVirtualKeyCode": code, "modifiers": if shift { 8 } else { 0 },
            });
            browser.call(Some(&self.session), "Input.dispatchKeyEvent", event)?;
        }
        Ok(())
    }

    /// Whether the page is laid out for the reader's dark (or light) colour scheme.
    pub fn prefer_dark(&self, browser: &mut Browser, dark: bool) -> Result<(), String> {
        let scheme = if dark { "dark" } else { "light" };
        let media = json!({ "features": [{ "name": "prefers-color-scheme", "value": scheme }] });
        browser.call(Some(&self.session), "Emulation.setEmulatedMedia", media)?;
        Ok(())
    }

    /// The whole page, `width` CSS pixels wide, as PNG bytes.
    pub fn screenshot(&self, browser: &mut Browser, width: u32) -> Result<Vec<u8>, String> {
        let height = self.eval(browser, "document.documentElement.scrollHeight")?;
        let height = height.as_f64().ok_or("no page height")?;
        let shot = browser.call(
            Some(&self.session),
            "Page.captureScreenshot",
            json!({
                "format": "png",
                "captureBeyondViewport": true,
                "clip": { "x": 0, "y": 0, "width": width, "height": height, "scale": 1 },
            }),
        )?;
        let data = shot["data"].as_str().ok_or("no screenshot data")?;
        use base64::Engine;
        base64::engine::general_purpose::STANDARD
            .decode(data)
            .map_err(|e| format!("the screenshot's base64: {e}"))
    }
}

//! The kernel's five sockets, bound as the connection file says and served
//! on a thread of their own (tokio, for the ZeroMQ crate): the heartbeat
//! echoes, the control channel is answered at once (an interrupt must
//! reach a cell that runs), shell requests go to the session's thread in
//! order, and what that thread sends goes out on the shell and IOPub
//! sockets. Messages are signed and checked with the connection's key by
//! `jupyter-zmq-client`; one that fails the check or does not parse is
//! logged on standard error and ignored.

use std::sync::mpsc;

use jupyter_protocol::{ConnectionInfo, IoPubWelcome, JupyterMessage};
use jupyter_zmq_client::{
    KernelControlConnection, KernelHeartbeatConnection, KernelIoPubXPubConnection, RouterRecvConnection,
    RouterSendConnection, SubscriptionEvent, create_kernel_control_connection, create_kernel_heartbeat_connection,
    create_kernel_iopub_xpub_connection, create_kernel_shell_connection, create_kernel_stdin_connection,
};
use tokio::sync::mpsc::{UnboundedReceiver, UnboundedSender, unbounded_channel};

/// Where the session's thread sends its messages.
#[derive(Debug, Clone)]
pub(crate) struct Outgoing {
    shell: UnboundedSender<JupyterMessage>,
    iopub: UnboundedSender<JupyterMessage>,
}

impl Outgoing {
    /// Sends a reply to a shell request.
    pub(crate) fn reply(&self, message: JupyterMessage) {
        // Gone only when the sockets' thread is, as the process ends.
        let _ = self.shell.send(message);
    }

    /// Publishes `message` on IOPub.
    pub(crate) fn iopub(&self, message: JupyterMessage) {
        let _ = self.iopub.send(message);
    }

    /// An outgoing end whose IOPub messages are kept in the receiver
    /// given with it, for tests.
    #[cfg(test)]
    pub(crate) fn kept() -> (Outgoing, UnboundedReceiver<JupyterMessage>) {
        let (shell, _) = unbounded_channel();
        let (iopub, published) = unbounded_channel();
        (Outgoing { shell, iopub }, published)
    }
}

/// What the control channel does with a request.
pub(crate) enum Control {
    /// Sends this reply.
    Reply(JupyterMessage),
    /// Sends this reply, then ends the process (a shutdown).
    ReplyAndEnd(JupyterMessage),
    /// Nothing (a request it does not know).
    Ignore,
}

/// How a control request is answered, on the sockets' thread.
pub(crate) type ControlAnswer = Box<dyn Fn(&JupyterMessage, &Outgoing) -> Control + Send>;

/// Binds the sockets of `info` under `session_id` and serves them on a
/// thread; gives the shell requests, in order, and where to send messages.
pub(crate) fn start(
    info: ConnectionInfo,
    session_id: String,
    control: ControlAnswer,
) -> Result<(mpsc::Receiver<JupyterMessage>, Outgoing), String> {
    let (requests, requested) = mpsc::channel();
    let (shell_out, shell_replies) = unbounded_channel();
    let (iopub_out, iopub_messages) = unbounded_channel();
    let outgoing = Outgoing { shell: shell_out, iopub: iopub_out };
    let (bound, bind_result) = mpsc::channel();
    let for_control = outgoing.clone();
    let spawned = std::thread::Builder::new().name("jupyter sockets".to_string()).spawn(move || {
        let runtime = match tokio::runtime::Builder::new_current_thread().enable_io().build() {
            Ok(runtime) => runtime,
            Err(error) => {
                let _ = bound.send(Err(format!("the kernel's event loop could not start: {error}")));
                return;
            }
        };
        runtime.block_on(async move {
            let sockets = match Sockets::bind(&info, &session_id).await {
                Ok(sockets) => sockets,
                Err(error) => {
                    let _ = bound.send(Err(error));
                    return;
                }
            };
            let _ = bound.send(Ok(()));
            let Sockets { heartbeat, control: control_socket, shell, iopub, stdin } = sockets;
            let (shell_send, shell_receive) = shell.split();
            tokio::join!(
                echo(heartbeat),
                answer_control(control_socket, control, for_control),
                forward_requests(shell_receive, requests),
                send_replies(shell_send, shell_replies),
                publish(iopub, iopub_messages),
            );
            // No input is ever asked for; the socket stays bound for clients that connect to it.
            drop(stdin);
        });
    });
    spawned.map_err(|error| format!("the kernel's sockets could not get a thread: {error}"))?;
    match bind_result.recv() {
        Ok(Ok(())) => Ok((requested, outgoing)),
        Ok(Err(error)) => Err(error),
        Err(_) => Err("the kernel's sockets stopped before they were bound".to_string()),
    }
}

/// The sockets, bound.
struct Sockets {
    heartbeat: KernelHeartbeatConnection,
    control: KernelControlConnection,
    shell: jupyter_zmq_client::KernelShellConnection,
    iopub: KernelIoPubXPubConnection,
    stdin: jupyter_zmq_client::KernelStdinConnection,
}

impl Sockets {
    async fn bind(info: &ConnectionInfo, session_id: &str) -> Result<Sockets, String> {
        let failed = |channel: &'static str| {
            let port = match channel {
                "shell" => info.shell_port,
                "iopub" => info.iopub_port,
                "stdin" => info.stdin_port,
                "control" => info.control_port,
                _ => info.hb_port,
            };
            move |error: jupyter_zmq_client::RuntimeError| {
                format!("the {channel} socket could not be bound at {}:{port}: {error}", info.ip)
            }
        };
        Ok(Sockets {
            heartbeat: create_kernel_heartbeat_connection(info).await.map_err(failed("heartbeat"))?,
            control: create_kernel_control_connection(info, session_id).await.map_err(failed("control"))?,
            shell: create_kernel_shell_connection(info, session_id).await.map_err(failed("shell"))?,
            iopub: create_kernel_iopub_xpub_connection(info, session_id).await.map_err(failed("iopub"))?,
            stdin: create_kernel_stdin_connection(info, session_id).await.map_err(failed("stdin"))?,
        })
    }
}

/// Logs a message that was ignored, and why.
fn ignored(channel: &str, error: impl std::fmt::Display) {
    crate::process::failure::report_failure(format!("kernel: a message on {channel} was ignored: {error}"));
}

async fn echo(mut heartbeat: KernelHeartbeatConnection) {
    while heartbeat.single_heartbeat().await.is_ok() {}
}

async fn answer_control(mut control: KernelControlConnection, answer: ControlAnswer, outgoing: Outgoing) {
    loop {
        let request = match control.read().await {
            Ok(request) => request,
            Err(error) => {
                ignored("control", error);
                continue;
            }
        };
        let (reply, ends) = match answer(&request, &outgoing) {
            Control::Reply(reply) => (reply, false),
            Control::ReplyAndEnd(reply) => (reply, true),
            Control::Ignore => continue,
        };
        if let Err(error) = control.send(reply).await {
            ignored("control", format!("its reply could not be sent: {error}"));
        }
        if ends {
            std::process::exit(0);
        }
    }
}

async fn forward_requests(mut shell: RouterRecvConnection, requests: mpsc::Sender<JupyterMessage>) {
    loop {
        match shell.read().await {
            Ok(request) => {
                if requests.send(request).is_err() {
                    return;
                }
            }
            Err(error) => ignored("shell", error),
        }
    }
}

async fn send_replies(mut shell: RouterSendConnection, mut replies: UnboundedReceiver<JupyterMessage>) {
    while let Some(reply) = replies.recv().await {
        if let Err(error) = shell.send(reply).await {
            ignored("shell", format!("a reply could not be sent: {error}"));
        }
    }
}

/// Publishes the session's messages, and welcomes each new subscriber
/// (the XPUB socket of JEP 65), so that a client knows when it hears all.
async fn publish(mut iopub: KernelIoPubXPubConnection, mut messages: UnboundedReceiver<JupyterMessage>) {
    loop {
        tokio::select! {
            message = messages.recv() => {
                let Some(message) = message else { return };
                if let Err(error) = iopub.send(message).await {
                    ignored("iopub", format!("a message could not be sent: {error}"));
                }
            }
            event = iopub.recv_subscription() => {
                if let Ok(SubscriptionEvent::Subscribe(topic)) = event
                    && let Err(error) = iopub.send(IoPubWelcome::new(topic).into()).await
                {
                    ignored("iopub", format!("the welcome could not be sent: {error}"));
                }
            }
        }
    }
}

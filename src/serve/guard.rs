//! What every request must show before it is answered: that it was sent
//! to this server by name (`Host`, against DNS rebinding: a page of
//! another site whose name was made to point at 127.0.0.1 sends its own
//! name), from a page of this server (`Origin`, when the browser says
//! one), with a body within bounds.

use std::io::Read;

/// The largest request body read: a model at its size limit, as JSON
/// (every byte escaped at worst), and the other fields.
pub const MAX_BODY: usize = crate::driver::MAX_SOURCE_BYTES * 2 + 64 * 1024;

/// The names this server answers to: `host:port` for each host it is
/// reached by.
pub struct Names {
    hosts: Vec<String>,
}

impl Names {
    /// The names of a server listening on `addr`: its address, and
    /// `localhost` for a loopback one.
    pub fn of(addr: std::net::SocketAddr) -> Names {
        let port = addr.port();
        let mut hosts = vec![match addr.ip() {
            std::net::IpAddr::V6(ip) => format!("[{ip}]:{port}"),
            ip => format!("{ip}:{port}"),
        }];
        if addr.ip().is_loopback() {
            hosts.extend(["localhost", "127.0.0.1", "[::1]"].map(|h| format!("{h}:{port}")));
        }
        hosts.dedup();
        Names { hosts }
    }

    /// The name the page is opened at.
    pub fn first(&self) -> &str {
        &self.hosts[0]
    }

    /// Why a request with these `Host` and `Origin` headers is refused,
    /// if it is.
    pub fn refuses(&self, host: Option<&str>, origin: Option<&str>) -> Option<String> {
        let Some(host) = host else {
            return Some("a request without a Host header".into());
        };
        if !self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host)) {
            return Some(format!("a request for host `{host}`, not this server"));
        }
        match origin {
            // Requests the browser makes for the page itself (navigation,
            // its script) may say no origin; a page elsewhere always does.
            None => None,
            Some(o) => {
                let ours = (o.strip_prefix("http://"))
                    .is_some_and(|h| self.hosts.iter().any(|n| n.eq_ignore_ascii_case(h)));
                (!ours).then(|| format!("a request from `{o}`, not a page of this server"))
            }
        }
    }
}

/// Reads a body of at most [`MAX_BODY`] bytes; `Err` when it is longer
/// or cannot be read.
pub fn body(reader: &mut dyn Read, declared: Option<usize>) -> Result<Vec<u8>, BodyError> {
    if declared.is_some_and(|n| n > MAX_BODY) {
        return Err(BodyError::TooLarge);
    }
    let mut bytes = Vec::new();
    let read = reader.take(MAX_BODY as u64 + 1).read_to_end(&mut bytes);
    match read {
        Err(_) => Err(BodyError::Unreadable),
        Ok(n) if n > MAX_BODY => Err(BodyError::TooLarge),
        Ok(_) => Ok(bytes),
    }
}

/// Why a body was not read.
#[derive(Debug, PartialEq, Eq)]
pub enum BodyError {
    TooLarge,
    Unreadable,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_this_servers_names_and_pages_are_answered() {
        let names = Names::of("127.0.0.1:8123".parse().unwrap());
        assert_eq!(names.refuses(Some("127.0.0.1:8123"), None), None);
        assert_eq!(
            names.refuses(Some("LOCALHOST:8123"), Some("http://localhost:8123")),
            None
        );
        // DNS rebinding: another name that resolves here.
        assert!(names.refuses(Some("evil.example:8123"), None).is_some());
        assert!(names.refuses(Some("127.0.0.1:9999"), None).is_some());
        assert!(names.refuses(None, None).is_some());
        // A page of another site posting here.
        let from = Some("http://evil.example");
        assert!(names.refuses(Some("127.0.0.1:8123"), from).is_some());
        assert!(names
            .refuses(Some("127.0.0.1:8123"), Some("null"))
            .is_some());
    }

    #[test]
    fn a_body_past_the_bound_is_refused_unread() {
        let big = vec![b'x'; MAX_BODY + 1];
        assert_eq!(body(&mut &big[..], None), Err(BodyError::TooLarge));
        assert_eq!(
            body(&mut &b""[..], Some(MAX_BODY + 1)),
            Err(BodyError::TooLarge)
        );
        assert_eq!(body(&mut &b"{}"[..], Some(2)), Ok(b"{}".to_vec()));
    }
}

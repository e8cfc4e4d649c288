//! The page, inside the binary: built from web/src by `web/build.sh`
//! (npm and esbuild, at development time), committed in web/dist, so that
//! nothing is fetched when it is served.

pub const INDEX_HTML: &str = include_str!("../../web/dist/index.html");
pub const PAGE_JS: &str = include_str!("../../web/dist/page.js");
pub const PAGE_CSS: &str = include_str!("../../web/dist/page.css");

//! Word wrapping of long report lines: the library's [`smash::report::wrap`].

pub use smash::report::wrap::wrap;

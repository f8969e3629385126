//! What the command-line tests share.

/// Runs `swarf ARGS` in-process; returns the exit status, standard output and standard error.
pub fn swarf(args: &[&str]) -> (i32, String, String) {
    let mut out = Vec::new();
    let mut err = Vec::new();
    let mut all = vec!["swarf"];
    all.extend_from_slice(args);
    let code = swarf_cli::run(all, &mut out, &mut err);
    (
        code,
        String::from_utf8_lossy(&out).into_owned(),
        String::from_utf8_lossy(&err).into_owned(),
    )
}

//! Arbitrary text is read as a `SETUP.toml`: no panic, and a setup that is read writes out as
//! a text that reads back to the same setup.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf_interp::Setup;

fuzz_target!(|bytes: &[u8]| {
    let text = String::from_utf8_lossy(bytes);
    let Ok(setup) = Setup::from_toml(&text) else {
        return;
    };
    let written = setup.to_toml().expect("a setup read can be written");
    let again = Setup::from_toml(&written).expect("a setup written can be read");
    assert_eq!(again, setup, "{written}");
});

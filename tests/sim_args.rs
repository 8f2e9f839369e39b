//! The simulators' shared command line (`examples/common/sim_args.rs`).
#[path = "../examples/common/sim_args.rs"]
mod sim_args;

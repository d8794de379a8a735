//! The binary's tests: it is run as a user runs it (exit codes, messages, files, pipes).

#[path = "../support/mod.rs"]
mod support;

mod amass;
mod analyze;
mod animator;
mod api;
mod app_conventions;
mod arrays;
mod batch;
mod batch_untrusted;
mod bvh;
mod bvh_gimbal;
mod bvh_stream;
mod bvh_untrusted;
mod diff;
mod errors;
mod fbx;
mod fbx_untrusted;
mod gltf;
mod gltf_real;
mod gltf_reduce;
mod gltf_tracks;
mod gltf_untrusted;
mod hard_cases;
mod logs;
mod numbers;
mod numeric_untrusted;
mod output;
mod plot;
mod readers;
mod reading;
mod readme;
mod reduce_bvh;
mod reduce_guarantee;
mod reduce_world;
mod reliability;
mod rot6d;
mod roundtrip;
mod usage;
mod usd;
mod usd_binary;
mod usd_untrusted;
mod validation;

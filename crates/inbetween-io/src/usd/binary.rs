//! Binary USD input: a usdc crate file, read by the openusd crate (0.6), and a usdz package,
//! whose root layer (its first entry, usdc or usda) is read as either (docs/spec.md §3, *USD
//! input*). The crate becomes the same [`Layer`] the text syntax is parsed into, holding the
//! same few fields (prims and their types, the skeletal properties, the layer's rate, unit and
//! up axis), so the meaning is [`super::read`]'s for both.
//!
//! Only the layer's own specs are read: its references, sublayers and payloads (asset paths)
//! are never opened — a file never makes the tool read another. openusd is given the bytes
//! only after [`super::bounds`] has checked what they claim, decodes only the values the reader
//! asks for (each checked first), and runs under `catch_unwind`: a panic in it is an input error
//! naming the file, never an abort.

use super::bounds::{self, Crate, Rep, ty};
use super::text::{KEPT_PROPERTIES, Layer, Prim, Property, Value};
use inbetween::error::{InputError, InputResult, shorten};
use openusd::sdf::{self, SpecType};
use openusd::usdc::CrateFile;
use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Whether bytes are a usdc crate file.
pub(crate) fn is_crate(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PXR-USDC")
}

/// Whether bytes are a zip archive (a usdz package when named or declared so).
pub(crate) fn is_zip(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK\x03\x04")
}

/// The root layer of a usdz package: its first entry, which the usdz format requires to be a
/// USD layer (`.usdc`, `.usda` or `.usd`), read by the tool's own bounded zip reader. A package
/// inside the package is refused; the other entries (textures, other layers) are not read.
pub(crate) fn package_root(bytes: &[u8], source: &str) -> InputResult<(String, Vec<u8>)> {
    // The zip reader is the `.npz` one: its messages name the container this one is.
    let entries = crate::amass::zip::entries(bytes, source)
        .map_err(|e| InputError::new(e.message().replacen("(.npz)", "(.usdz)", 1)))?;
    let Some(first) = entries.into_iter().next() else {
        return Err(InputError::new(format!(
            "{source}: an empty usdz package (no root layer)"
        )));
    };
    let name = first.name.to_ascii_lowercase();
    if ![".usdc", ".usda", ".usd"].iter().any(|e| name.ends_with(e)) {
        return Err(InputError::new(format!(
            "{source}: the usdz package's first entry \"{}\" is not a USD layer (.usdc, .usda, \
             .usd), which the usdz format puts first",
            shorten(&first.name)
        )));
    }
    let data = first.data(source)?.into_owned();
    Ok((first.name, data))
}

thread_local! {
    /// Set while openusd runs on this thread: its panics are caught and become input errors, so
    /// the panic hook keeps their message here instead of printing it.
    static CAUGHT: RefCell<Option<Option<String>>> = const { RefCell::new(None) };
}

/// Installs (once) a panic hook that stays silent for a panic inside openusd on a thread that
/// catches it, and hands every other panic to the hook that was there before.
fn quiet_hook() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let caught = CAUGHT.with(|c| {
                let mut c = c.borrow_mut();
                match c.as_mut() {
                    Some(slot) => {
                        let msg = info
                            .payload()
                            .downcast_ref::<&str>()
                            .map(|s| s.to_string())
                            .or_else(|| info.payload().downcast_ref::<String>().cloned());
                        *slot = msg;
                        true
                    }
                    None => false,
                }
            });
            if !caught {
                previous(info);
            }
        }));
    });
}

/// Reads the usdc crate `bytes` into a layer (see the module documentation).
pub(crate) fn read_crate(bytes: &[u8], source: &str) -> InputResult<Layer> {
    let fail = |what: String| InputError::new(format!("{source}: usdc: {what}"));
    let mut bounds = bounds::check_structure(bytes).map_err(fail)?;
    quiet_hook();
    CAUGHT.with(|c| *c.borrow_mut() = Some(None));
    let result = catch_unwind(AssertUnwindSafe(|| convert(bytes, &mut bounds)));
    let message = CAUGHT.with(|c| c.borrow_mut().take()).flatten();
    match result {
        Ok(Ok(layer)) => Ok(layer),
        Ok(Err(e)) => Err(fail(e)),
        Err(_) => Err(fail(format!(
            "openusd could not read it ({}; corrupt?)",
            shorten(message.as_deref().unwrap_or("it stopped"))
        ))),
    }
}

/// The crate's specs as a layer.
fn convert<'b>(bytes: &'b [u8], bounds: &mut Crate<'b>) -> Result<Layer, String> {
    let mut file = CrateFile::open(Cursor::new(bytes)).map_err(|e| format!("{e:#}"))?;
    file.validate().map_err(|e| format!("{e:#}"))?;
    let mut by_path: HashMap<String, usize> = HashMap::with_capacity(file.specs.len());
    for (k, spec) in file.specs.iter().enumerate() {
        by_path
            .entry(file.paths[spec.path_index].as_str().to_string())
            .or_insert(k);
    }
    let mut reader = Reader {
        file: &mut file,
        bounds,
    };
    let mut layer = Layer::default();
    let root = by_path.get("/").copied().ok_or("no pseudo-root spec")?;
    for (key, allowed) in [
        ("timeCodesPerSecond", &[ty::DOUBLE, ty::FLOAT][..]),
        ("framesPerSecond", &[ty::DOUBLE, ty::FLOAT][..]),
        ("metersPerUnit", &[ty::DOUBLE, ty::FLOAT][..]),
        ("upAxis", &[ty::TOKEN][..]),
    ] {
        if let Some(v) = reader.get(root, key, allowed)? {
            layer.metadata.push((key.to_string(), plain(v)));
        }
    }
    // The prims depth first, in each parent's primChildren order (the text's order), each path
    // once.
    let mut seen: HashSet<String> = HashSet::new();
    let mut stack: Vec<(String, Option<usize>)> = reader
        .children(root, "")?
        .into_iter()
        .rev()
        .map(|p| (p, None))
        .collect();
    while let Some((path, parent)) = stack.pop() {
        let Some(&spec) = by_path.get(&path) else {
            continue;
        };
        if reader.file.specs[spec].spec_type != SpecType::Prim || !seen.insert(path.clone()) {
            continue;
        }
        let type_name = match reader.get(spec, "typeName", &[ty::TOKEN])? {
            Some(sdf::Value::Token(t)) => t.as_str().to_string(),
            _ => String::new(),
        };
        let mut properties = Vec::new();
        for name in KEPT_PROPERTIES {
            if let Some(&p) = by_path.get(&format!("{path}.{name}")) {
                properties.push(reader.property(p, name)?);
            }
        }
        let index = layer.prims.len();
        layer.prims.push(Prim {
            name: path.rsplit('/').next().unwrap_or_default().to_string(),
            parent,
            type_name,
            properties,
            line: 0,
        });
        for child in reader.children(spec, &path)?.into_iter().rev() {
            stack.push((child, Some(index)));
        }
    }
    Ok(layer)
}

/// The crate file and the bounds its values are checked against.
struct Reader<'f, 'b> {
    file: &'f mut CrateFile<Cursor<&'b [u8]>>,
    bounds: &'f mut Crate<'b>,
}

impl Reader<'_, '_> {
    /// The value of field `name` of spec `spec`, checked ([`Crate::value`]) then decoded.
    fn get(
        &mut self,
        spec: usize,
        name: &str,
        allowed: &[u8],
    ) -> Result<Option<sdf::Value>, String> {
        let mut set = Some(self.file.specs[spec].fieldset_index);
        while let Some(i) = set {
            let Some(&Some(f)) = self.file.fieldsets.get(i) else {
                return Ok(None);
            };
            let field = self
                .file
                .fields
                .get(f)
                .ok_or("a field index out of range")?;
            let token = self.file.tokens.get(field.token_index);
            if token.is_some_and(|t| t == name) {
                let rep = field.value_rep;
                self.bounds.value(Rep(rep.0), allowed, name)?;
                return self
                    .file
                    .value(rep)
                    .map(Some)
                    .map_err(|e| format!("{name}: {e:#}"));
            }
            set = Some(i + 1);
        }
        Ok(None)
    }

    /// The paths of the children a prim (or the pseudo-root, `path` empty) lists.
    fn children(&mut self, spec: usize, path: &str) -> Result<Vec<String>, String> {
        Ok(match self.get(spec, "primChildren", &[ty::TOKEN_VECTOR])? {
            Some(sdf::Value::TokenVec(names)) => names
                .iter()
                .map(|n| format!("{path}/{}", n.as_str()))
                .collect(),
            _ => Vec::new(),
        })
    }

    /// An attribute or relationship as the text parser keeps it.
    fn property(&mut self, spec: usize, name: &str) -> Result<Property, String> {
        const ARRAYS: [u8; 9] = [
            ty::TOKEN,
            ty::MATRIX4D,
            ty::QUATF,
            ty::QUATD,
            ty::QUATH,
            ty::VEC3F,
            ty::VEC3D,
            ty::VEC3H,
            ty::DOUBLE,
        ];
        let mut prop = Property {
            name: name.to_string(),
            type_name: String::new(),
            value: None,
            samples: None,
            line: 0,
        };
        if self.file.specs[spec].spec_type == SpecType::Relationship {
            prop.type_name = "rel".into();
            if let Some(sdf::Value::PathListOp(op)) =
                self.get(spec, "targetPaths", &[ty::PATH_LIST_OP])?
            {
                let mut targets: Vec<Value> = [
                    &op.explicit_items,
                    &op.prepended_items,
                    &op.added_items,
                    &op.appended_items,
                ]
                .into_iter()
                .flatten()
                .map(|p| Value::Path(p.as_str().to_string()))
                .collect();
                prop.value = Some(if targets.len() == 1 {
                    targets.remove(0)
                } else {
                    Value::List(targets)
                });
            }
            return Ok(prop);
        }
        if let Some(sdf::Value::Token(t)) = self.get(spec, "typeName", &[ty::TOKEN])? {
            prop.type_name = t.as_str().to_string();
        }
        let mut with_samples = ARRAYS.to_vec();
        with_samples.push(ty::TIME_SAMPLES);
        prop.value = self.get(spec, "default", &ARRAYS)?.map(plain);
        if let Some(sdf::Value::TimeSamples(s)) = self.get(spec, "timeSamples", &with_samples)? {
            prop.samples = Some(s.into_iter().map(|(c, v)| (c, plain(v))).collect());
        }
        Ok(prop)
    }
}

/// An openusd value as the text parser's: numbers, tokens, and arrays of vectors, quaternions
/// (`(w, x, y, z)`, real first as in the text) and row-major matrices.
fn plain(v: sdf::Value) -> Value {
    use sdf::Value as S;
    let list = |items: Vec<Vec<f64>>| Value::List(items.into_iter().map(Value::Numbers).collect());
    match v {
        S::Double(x) => Value::Num(x),
        S::Float(x) => Value::Num(f64::from(x)),
        S::Token(t) => Value::Str(t.as_str().to_string()),
        S::TokenVec(v) => Value::List(
            v.iter()
                .map(|t| Value::Str(t.as_str().to_string()))
                .collect(),
        ),
        S::DoubleVec(v) => Value::Numbers(v),
        S::Matrix4dVec(v) => list(v.into_iter().map(|m| m.0.to_vec()).collect()),
        S::QuatfVec(v) => list(
            v.into_iter()
                .map(|q| [q.w, q.x, q.y, q.z].map(f64::from).to_vec())
                .collect(),
        ),
        S::QuatdVec(v) => list(v.into_iter().map(|q| vec![q.w, q.x, q.y, q.z]).collect()),
        S::QuathVec(v) => list(
            v.into_iter()
                .map(|q| [q.w, q.x, q.y, q.z].map(|h| f64::from(h.to_f32())).to_vec())
                .collect(),
        ),
        S::Vec3fVec(v) => list(
            v.into_iter()
                .map(|p| [p.x, p.y, p.z].map(f64::from).to_vec())
                .collect(),
        ),
        S::Vec3dVec(v) => list(v.into_iter().map(|p| vec![p.x, p.y, p.z]).collect()),
        S::Vec3hVec(v) => list(
            v.into_iter()
                .map(|p| [p.x, p.y, p.z].map(|h| f64::from(h.to_f32())).to_vec())
                .collect(),
        ),
        _ => Value::Other,
    }
}

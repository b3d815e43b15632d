//! The ONNX form of an exported controller: the network as an ONNX graph (opset 13) in double
//! precision, its input the eight raw readings (clamped to 1023 and scaled by the graph as the
//! C and the simulator do), its output the two motor outputs. The protobuf messages are declared here for the
//! subset of `onnx.proto` the graph needs (field numbers as in ONNX 1.x) and written with
//! `prost`.
//!
//! An ONNX runtime agrees with the simulator to about 1e-15, not bit for bit: its `MatMul` may
//! add the products in another order or fuse them, and its `Sigmoid` uses its own `exp`.

use prost::Message;

use super::ExportedController;
use crate::simulation::controller::OUTPUTS;

/// `TensorProto.DataType.DOUBLE`.
const DOUBLE: i32 = 11;

#[derive(Clone, PartialEq, Message)]
struct ModelProto {
    #[prost(int64, tag = "1")]
    ir_version: i64,
    #[prost(string, tag = "2")]
    producer_name: String,
    #[prost(string, tag = "3")]
    producer_version: String,
    #[prost(string, tag = "6")]
    doc_string: String,
    #[prost(message, optional, tag = "7")]
    graph: Option<GraphProto>,
    #[prost(message, repeated, tag = "8")]
    opset_import: Vec<OperatorSetIdProto>,
    #[prost(message, repeated, tag = "14")]
    metadata_props: Vec<StringStringEntryProto>,
}

#[derive(Clone, PartialEq, Message)]
struct OperatorSetIdProto {
    #[prost(string, tag = "1")]
    domain: String,
    #[prost(int64, tag = "2")]
    version: i64,
}

#[derive(Clone, PartialEq, Message)]
struct StringStringEntryProto {
    #[prost(string, tag = "1")]
    key: String,
    #[prost(string, tag = "2")]
    value: String,
}

#[derive(Clone, PartialEq, Message)]
struct GraphProto {
    #[prost(message, repeated, tag = "1")]
    node: Vec<NodeProto>,
    #[prost(string, tag = "2")]
    name: String,
    #[prost(message, repeated, tag = "5")]
    initializer: Vec<TensorProto>,
    #[prost(message, repeated, tag = "11")]
    input: Vec<ValueInfoProto>,
    #[prost(message, repeated, tag = "12")]
    output: Vec<ValueInfoProto>,
}

#[derive(Clone, PartialEq, Message)]
struct NodeProto {
    #[prost(string, repeated, tag = "1")]
    input: Vec<String>,
    #[prost(string, repeated, tag = "2")]
    output: Vec<String>,
    #[prost(string, tag = "3")]
    name: String,
    #[prost(string, tag = "4")]
    op_type: String,
}

#[derive(Clone, PartialEq, Message)]
struct TensorProto {
    #[prost(int64, repeated, tag = "1")]
    dims: Vec<i64>,
    #[prost(int32, tag = "2")]
    data_type: i32,
    #[prost(string, tag = "8")]
    name: String,
    #[prost(double, repeated, tag = "10")]
    double_data: Vec<f64>,
}

#[derive(Clone, PartialEq, Message)]
struct ValueInfoProto {
    #[prost(string, tag = "1")]
    name: String,
    #[prost(message, optional, tag = "2")]
    r#type: Option<TypeProto>,
}

#[derive(Clone, PartialEq, Message)]
struct TypeProto {
    #[prost(message, optional, tag = "1")]
    tensor_type: Option<TensorType>,
}

#[derive(Clone, PartialEq, Message)]
struct TensorType {
    #[prost(int32, tag = "1")]
    elem_type: i32,
    #[prost(message, optional, tag = "2")]
    shape: Option<TensorShapeProto>,
}

#[derive(Clone, PartialEq, Message)]
struct TensorShapeProto {
    #[prost(message, repeated, tag = "1")]
    dim: Vec<Dimension>,
}

#[derive(Clone, PartialEq, Message)]
struct Dimension {
    #[prost(int64, optional, tag = "1")]
    dim_value: Option<i64>,
    #[prost(string, optional, tag = "2")]
    dim_param: Option<String>,
}

/// A `[N, width]` double tensor named `name` (N the batch of steps).
fn batch_of(name: &str, width: i64) -> ValueInfoProto {
    let dims = vec![
        Dimension {
            dim_value: None,
            dim_param: Some("N".into()),
        },
        Dimension {
            dim_value: Some(width),
            dim_param: None,
        },
    ];
    ValueInfoProto {
        name: name.into(),
        r#type: Some(TypeProto {
            tensor_type: Some(TensorType {
                elem_type: DOUBLE,
                shape: Some(TensorShapeProto { dim: dims }),
            }),
        }),
    }
}

fn tensor(name: &str, dims: &[i64], data: Vec<f64>) -> TensorProto {
    TensorProto {
        dims: dims.to_vec(),
        data_type: DOUBLE,
        name: name.into(),
        double_data: data,
    }
}

fn node(op: &str, inputs: &[&str], output: &str) -> NodeProto {
    NodeProto {
        input: inputs.iter().map(|s| s.to_string()).collect(),
        output: vec![output.into()],
        name: output.into(),
        op_type: op.into(),
    }
}

/// The network's weights as ONNX initialisers: `w1` `[N, H]` (N the robot's sensors), `b1`
/// `[H]`, `w2` `[H, 2]`, `b2` `[2]` (transposed from the genome's per-unit rows) and the
/// reading scale (the robot's `reading_max`).
fn initialisers(c: &ExportedController) -> Vec<TensorProto> {
    let h = c.shape.hidden();
    let n = c.robot.sensors;
    let (hidden_w, out_w) = c.weights.split_at(h * (n + 1));
    let w1 = (0..n)
        .flat_map(|i| (0..h).map(move |j| hidden_w[j * (n + 1) + 1 + i]))
        .collect();
    let b1 = (0..h).map(|j| hidden_w[j * (n + 1)]).collect();
    let w2 = (0..h)
        .flat_map(|j| (0..OUTPUTS).map(move |o| out_w[o * (h + 1) + 1 + j]))
        .collect();
    let b2 = (0..OUTPUTS).map(|o| out_w[o * (h + 1)]).collect();
    let h = h as i64;
    vec![
        tensor("reading_max", &[], vec![c.robot.reading_max]),
        tensor("w1", &[n as i64, h], w1),
        tensor("b1", &[h], b1),
        tensor("w2", &[h, OUTPUTS as i64], w2),
        tensor("b2", &[OUTPUTS as i64], b2),
    ]
}

/// The ONNX model's bytes.
pub(crate) fn model(c: &ExportedController) -> Vec<u8> {
    let nodes = vec![
        // Readings above reading_max count as reading_max, as in the C and the JSON's scaling.
        node("Min", &["ir", "reading_max"], "ir_clamped"),
        node("Div", &["ir_clamped", "reading_max"], "x"),
        node("MatMul", &["x", "w1"], "x_w1"),
        node("Add", &["x_w1", "b1"], "hidden_sum"),
        node("Sigmoid", &["hidden_sum"], "hidden"),
        node("MatMul", &["hidden", "w2"], "hidden_w2"),
        node("Add", &["hidden_w2", "b2"], "output_sum"),
        node("Sigmoid", &["output_sum"], "motors"),
    ];
    let graph = GraphProto {
        node: nodes,
        name: format!("fuzzymotiv_{}_{}_2", c.robot.sensors, c.shape.hidden()),
        initializer: initialisers(c),
        input: vec![batch_of("ir", c.robot.sensors as i64)],
        output: vec![batch_of("motors", OUTPUTS as i64)],
    };
    let meta = |k: &str, v: String| StringStringEntryProto {
        key: k.into(),
        value: v,
    };
    let model = ModelProto {
        ir_version: 8,
        producer_name: "fuzzymotiv".into(),
        producer_version: crate::VERSION.into(),
        doc_string: format!(
            "An evolved fuzzymotiv controller: ir [N, {n}] raw readings 0..{max} (a larger one counts as {max}) -> motors [N, 2] (mL, mR in [0, 1]; wheel speed (2m - 1) * v_max). Agrees with the simulator to ~1e-15, not bit for bit (MatMul's summation order, the runtime's exp).",
            n = c.robot.sensors,
            max = c.robot.reading_max
        ),
        graph: Some(graph),
        opset_import: vec![OperatorSetIdProto {
            domain: String::new(),
            version: 13,
        }],
        metadata_props: vec![
            meta("provenance", crate::provenance()),
            meta("v_max", format!("{}", c.v_max)),
            meta("action_tolerance", format!("{}", c.tolerance)),
        ],
    };
    model.encode_to_vec()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::{MlpShape, TrialParams};

    /// The graph run by hand (its seven operators, `[N, K]` tensors row by row) on `ir`.
    fn run(model: &[u8], ir: &[[f64; 8]]) -> Vec<f64> {
        let graph = ModelProto::decode(model).unwrap().graph.unwrap();
        let mut values: std::collections::HashMap<String, (Vec<i64>, Vec<f64>)> =
            (graph.initializer.iter())
                .map(|t| (t.name.clone(), (t.dims.clone(), t.double_data.clone())))
                .collect();
        let rows = ir.len() as i64;
        values.insert("ir".into(), (vec![rows, 8], ir.concat()));
        for n in &graph.node {
            let (a, b) = (&values[&n.input[0]], n.input.get(1).map(|i| &values[i]));
            let pair = |f: fn(f64, f64) -> f64| {
                let (_, b) = b.unwrap();
                let data = (a.1.iter().enumerate())
                    .map(|(i, &x)| f(x, b[i % b.len()]))
                    .collect();
                (a.0.clone(), data)
            };
            let out = match n.op_type.as_str() {
                "Min" => pair(f64::min),
                "Div" => pair(|x, y| x / y),
                "Add" => pair(|x, y| x + y),
                "Sigmoid" => (
                    a.0.clone(),
                    a.1.iter().map(|x| 1.0 / (1.0 + (-x).exp())).collect(),
                ),
                "MatMul" => {
                    let (bd, bv) = b.unwrap();
                    let (k, m) = (bd[0] as usize, bd[1] as usize);
                    let data = (a.1.chunks(k))
                        .flat_map(|row| {
                            (0..m).map(move |j| (0..k).map(|i| row[i] * bv[i * m + j]).sum())
                        })
                        .collect();
                    (vec![a.0[0], m as i64], data)
                }
                op => panic!("operator {op} not run here"),
            };
            values.insert(n.output[0].clone(), out);
        }
        values.remove("motors").unwrap().1
    }

    /// Issue #52 item 7: a reading above 1023 (65535 from a 16-bit sensor) counts as 1023 in
    /// the ONNX graph, as in the C and the JSON's scaling, so it gives the motors of 1023.
    #[test]
    fn onnx_clamps_readings_above_1023_as_c_and_json_do() {
        let shape = MlpShape::default();
        let genome: Vec<f64> = (0..shape.genome_len())
            .map(|i| ((i * 7 % 11) as f64 - 5.0) / 3.0)
            .collect();
        let c = ExportedController::new(shape, &genome, &TrialParams::default()).unwrap();
        let model = c.onnx();
        let at = |v: f64| [v, 0.0, 200.0, v, 1023.0, 0.0, v, 5.0];
        let motors = run(&model, &[at(65535.0), at(1023.0), at(1024.5)]);
        assert_eq!(motors[0..2], motors[2..4], "65535 counts as 1023");
        assert_eq!(motors[4..6], motors[2..4], "1024.5 counts as 1023");
        let lower = run(&model, &[at(512.0)]);
        assert_ne!(
            lower[..],
            motors[2..4],
            "readings below 1023 are read as they are"
        );
    }
}

//! `host-sim serve`'s simulation and API without a browser: clicked
//! events, the fault and reset path, plant automata, physical plants,
//! Petri nets, and a served run replaying to the same trace.

use codegen::backend::Backend;
use host_sim::inputs;
use host_sim::replay::replay;
use host_sim::serve::http::App;
use host_sim::serve::{PlantChoice, Session};
use host_sim::{trace, Sim};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn model(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(file)
}

fn session(file: &str, plant: PlantChoice) -> Session {
    Session::load(&model(file), Backend::Table, plant).unwrap()
}

fn app(file: &str) -> App {
    App {
        session: session(file, PlantChoice::Auto),
        file: file.to_owned(),
    }
}

/// The state the API sends after `method path body`.
fn call(app: &mut App, method: &str, path: &str, body: &str) -> Value {
    let reply = app.handle(method, path, body.as_bytes());
    let value: Value = serde_json::from_slice(&reply.body).unwrap();
    assert_eq!(reply.status, 200, "{method} {path} {body}: {value}");
    value
}

/// Sets a raw input through the API.
fn set(app: &mut App, input: &str, value: bool) {
    let body = serde_json::json!({ "name": input, "value": value }).to_string();
    call(app, "POST", "/api/input", &body);
}

fn state(session: &Session, supervisor: &str) -> String {
    session.sim().state(supervisor).unwrap()
}

/// The run's inputs file replayed through a fresh controller gives the
/// run's trace file, byte for byte.
fn assert_replays(session: &Session) {
    let project = session.project();
    let rows = inputs::parse(
        session.inputs_csv().unwrap(),
        Path::new("inputs.csv"),
        project,
    )
    .unwrap();
    assert_eq!(rows.len() as u64, session.scans());
    let mut sim = Sim::new(project.clone(), Backend::Table).unwrap();
    let replayed = trace::to_csv(project, &replay(&mut sim, &rows).unwrap());
    assert_eq!(replayed, session.trace_csv().unwrap());
}

#[test]
fn the_press_cycle_clicked_event_by_event_replays_to_the_same_trace() {
    let mut s = session("press.plc.toml", PlantChoice::Auto);
    assert_eq!(s.machine().kind(), "supervisors");
    s.set_input("top_ls", true).unwrap();
    s.click("auto").unwrap();
    assert_eq!(state(&s, "press"), "2");
    // The button is released once its event is seen.
    assert!(!s.raw()[s.project().input("auto_pb").unwrap()]);
    // The part sensor is debounced over 3 scans: the click waits for it.
    let before = s.scans();
    s.click("part_in").unwrap();
    assert_eq!(state(&s, "press"), "3");
    assert!(s.scans() - before >= 3, "{} scans", s.scans() - before);
    assert!(s.sim().output("down_sol").unwrap());
    s.set_input("top_ls", false).unwrap();
    s.click("at_bottom").unwrap();
    assert_eq!(state(&s, "press"), "4");
    assert!(s.sim().output("up_sol").unwrap());
    s.set_input("bottom_ls", false).unwrap();
    s.click("at_top").unwrap();
    s.click("part_out").unwrap();
    assert_eq!(state(&s, "press"), "2");
    assert!(s.fault().is_none());
    let events: Vec<String> = s.log().flat_map(|e| e.events.clone()).collect();
    assert_eq!(
        events,
        ["auto", "part_in", "at_bottom", "at_top", "part_out"]
    );
    assert_replays(&s);
}

/// The ram at the top, then the auto button: the press in state 2.
fn auto_at_the_top(app: &mut App) {
    call(
        app,
        "POST",
        "/api/input",
        r#"{"name":"top_ls","value":true}"#,
    );
    let st = call(app, "POST", "/api/event", r#"{"name":"auto"}"#);
    assert_eq!(st["supervisors"][0]["name"], "2");
}

#[test]
fn an_unexpected_event_faults_to_safe_outputs_and_the_reset_input_recovers() {
    let mut app = app("press.plc.toml");
    auto_at_the_top(&mut app);
    let st = call(&mut app, "GET", "/api/state", "");
    let at_bottom = st["uncontrollable"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["event"] == "at_bottom")
        .unwrap();
    assert_eq!(at_bottom["expected"], false, "{at_bottom}");
    let st = call(&mut app, "POST", "/api/event", r#"{"name":"at_bottom"}"#);
    assert_eq!(st["fault"]["cause"], "Unexpected:at_bottom", "{st}");
    assert_eq!(
        st["outputs"],
        serde_json::json!([false, false, false, false])
    );
    let last = st["log"].as_array().unwrap().last().unwrap().clone();
    assert_eq!(last["unexpected"], serde_json::json!(["at_bottom"]));
    // Reset: the reset input's rising edge leaves fault mode.
    set(&mut app, "reset_pb", true);
    let st = call(&mut app, "POST", "/api/step", r#"{"scans":1}"#);
    assert!(st["fault"].is_null(), "{st}");
    assert_eq!(st["supervisors"][0]["name"], "1");
    assert_eq!(st["counters"]["faults"], 1);
    assert_replays(&app.session);
}

#[test]
fn plant_automata_move_with_the_executed_events_and_drive_a_run_without_faults() {
    let mut s = session("conveyor.plc.toml", PlantChoice::Auto);
    let host_sim::serve::machine::Machine::Automata(plant) = s.machine() else {
        panic!("the conveyor synthesises from plant files");
    };
    let names: Vec<&str> = plant.components().iter().map(|a| a.name()).collect();
    assert_eq!(names, ["sensor", "belt", "runon"]);
    let before = plant.state_names();
    s.set_driver(host_sim::serve::session::Driver::Random);
    s.step(5_000);
    let log: Vec<_> = s.log().cloned().collect();
    assert!(log.iter().any(|e| !e.events.is_empty()), "{log:?}");
    assert!(s.fault().is_none(), "{:?}", s.fault());
    // The supervisor was synthesised against these automata: they can
    // always do what it executes.
    assert!(
        log.iter()
            .all(|e| !e.note.as_deref().unwrap_or("").contains("cannot do")),
        "{log:?}"
    );
    let host_sim::serve::machine::Machine::Automata(plant) = s.machine() else {
        unreachable!()
    };
    assert_ne!(plant.state_names(), before);
    assert_replays(&s);
}

#[test]
fn an_unobservable_plant_event_is_a_button_that_moves_the_plant_unseen() {
    let mut app = app("breakdown.plc.toml");
    let model = call(&mut app, "GET", "/api/model", "");
    assert_eq!(
        model["plant"]["actions"],
        serde_json::json!([{ "name": "b1", "label": "b1 (unseen)" }]),
        "{model}"
    );
    // M1 idle: it cannot break down; the refusal names the plant's states.
    let reply = app.handle("POST", "/api/action", br#"{"name":"b1"}"#);
    let text = String::from_utf8_lossy(&reply.body).into_owned();
    assert_eq!(reply.status, 400, "{text}");
    assert!(text.contains("M1 idle"), "{text}");
    // Started (scan 0 commands s1), M1 breaks down: the plant moves, the
    // controller's state does not, and a repair is then expected.
    call(&mut app, "POST", "/api/step", r#"{"scans":1}"#);
    let before = state(&app.session, "cell");
    assert!(
        before.starts_with("{working.idle.empty.clear,down"),
        "{before}"
    );
    call(&mut app, "POST", "/api/action", r#"{"name":"b1"}"#);
    let host_sim::serve::machine::Machine::Automata(plant) = app.session.machine() else {
        panic!("the breakdown cell runs on its plant automata");
    };
    assert_eq!(plant.state_names()[0], "down");
    call(&mut app, "POST", "/api/step", r#"{"scans":1}"#);
    assert_eq!(state(&app.session, "cell"), before);
    // Repaired, M1 is started again at once.
    call(&mut app, "POST", "/api/event", r#"{"name":"r1"}"#);
    let executed: Vec<String> = app.session.log().flat_map(|e| e.events.clone()).collect();
    assert_eq!(executed, ["s1", "r1", "s1"]);
    let host_sim::serve::machine::Machine::Automata(plant) = app.session.machine() else {
        unreachable!()
    };
    assert_eq!(plant.state_names()[0], "working");
    // The random driver breaks M1 down now and then, without a fault.
    app.session
        .set_driver(host_sim::serve::session::Driver::Random);
    app.session.step(20_000);
    assert!(app.session.fault().is_none(), "{:?}", app.session.fault());
    let log: Vec<_> = app.session.log().cloned().collect();
    let unseen = log
        .iter()
        .filter(|e| e.note.as_deref().unwrap_or("").contains("b1 (unseen)"))
        .count();
    assert!(unseen >= 5, "{unseen} breakdowns");
    assert!(
        log.iter()
            .all(|e| !e.note.as_deref().unwrap_or("").contains("cannot do")),
        "a command the plant could not follow: {:?}",
        log.iter()
            .filter(|e| e.note.as_deref().unwrap_or("").contains("cannot do"))
            .take(3)
            .collect::<Vec<_>>()
    );
    assert_replays(&app.session);
}

#[test]
fn the_boiler_runs_on_its_physics_and_its_inputs_replay() {
    let mut app = app("boiler/boiler.plc.toml");
    let model = call(&mut app, "GET", "/api/model", "");
    assert_eq!(model["plant"]["kind"], "boiler");
    assert_eq!(model["plant"]["analog"][0]["name"], "bath_c");
    let refused = app.handle("POST", "/api/input", br#"{"name":"sel_high","value":true}"#);
    assert_eq!(refused.status, 400);
    call(
        &mut app,
        "POST",
        "/api/action",
        r#"{"name":"selector_high"}"#,
    );
    let st = call(&mut app, "POST", "/api/run", r#"{"scans":12000}"#);
    assert_eq!(st["ran"], 12_000);
    // The first scan ran at start: the plant's inputs at rest.
    assert_eq!(st["scan"], 12_001);
    let events: Vec<&str> = st["log"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|e| e["events"].as_array().unwrap())
        .map(|e| e.as_str().unwrap())
        .collect();
    assert!(events.contains(&"mf_on"), "{events:?}");
    assert!(st["fault"].is_null(), "{st}");
    let bath = st["plant"]["analog"][0].as_f64().unwrap();
    assert!(bath > 20.0, "bath {bath}");
    let h = call(&mut app, "GET", "/api/history?points=50", "");
    assert_eq!(h["time_ms"].as_array().unwrap().len(), 50);
    assert_eq!(h["time_ms"][49], 120_000);
    assert_eq!(h["analog"].as_array().unwrap().len(), 4);
    assert_replays(&app.session);
}

#[test]
fn a_net_says_which_place_holds_a_command_back() {
    let mut app = app("petri/mixers.plc.toml");
    let model = call(&mut app, "GET", "/api/model", "");
    let places = model["nets"][0]["places"].as_array().unwrap();
    assert!(places.iter().any(|p| p["control"] == true), "{places:?}");
    // Mixer A starts: t1 takes the supply's control place.
    set(&mut app, "start_a", true);
    let st = call(&mut app, "POST", "/api/step", r#"{"scans":2}"#);
    let executed: Vec<&Value> = st["log"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|e| e["events"].as_array().unwrap())
        .collect();
    assert_eq!(executed, [&Value::from("t1")]);
    // Mixer B may not start while A holds the supply: the control place
    // disables it.
    let t5 = st["commands"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["event"] == "t5")
        .unwrap();
    assert_eq!(t5["enabled"], false);
    let why = t5["disabled_by"][0]["why"].as_str().unwrap();
    assert!(why.contains("place"), "{why}");
    let marking = &st["markings"][0];
    assert_eq!(marking.as_array().unwrap().len(), places.len());
    assert_replays(&app.session);
}

#[test]
fn bad_requests_are_refused_with_a_message() {
    let mut app = app("press.plc.toml");
    let error = |app: &mut App, method: &str, path: &str, body: &str| {
        let reply = app.handle(method, path, body.as_bytes());
        let value: Value = serde_json::from_slice(&reply.body).unwrap();
        (
            reply.status,
            value["error"].as_str().unwrap_or("").to_owned(),
        )
    };
    let (status, text) = error(&mut app, "POST", "/api/step", r#"{"scans":0}"#);
    assert_eq!(status, 400);
    assert!(text.contains("scans must be"), "{text}");
    let (status, text) = error(&mut app, "POST", "/api/step", r#"{"scan":1}"#);
    assert_eq!(status, 400);
    assert!(text.contains("unknown field"), "{text}");
    let (status, text) = error(&mut app, "POST", "/api/event", r#"{"name":"nope"}"#);
    assert_eq!(
        (status, text.as_str()),
        (400, "`nope` is not an event of the project")
    );
    let (status, text) = error(&mut app, "POST", "/api/input", r#"{"name":"x","value":1}"#);
    assert_eq!(status, 400);
    assert!(text.contains("bad request body"), "{text}");
    let (status, _) = error(&mut app, "GET", "/api/nothing", "");
    assert_eq!(status, 405);
    let (status, _) = error(&mut app, "GET", "/etc/passwd", "");
    assert_eq!(status, 404);
    let (status, text) = error(&mut app, "POST", "/api/history?points=x", "");
    assert_eq!(status, 405, "{text}");
    let (status, text) = error(&mut app, "GET", "/api/history?points=x", "");
    assert_eq!(status, 400);
    assert!(text.contains("`points`"), "{text}");
    let page = app.handle("GET", "/", b"");
    assert_eq!(
        (page.status, page.content_type),
        (200, "text/html; charset=utf-8")
    );
    // Nothing refused moved the simulation.
    assert_eq!(app.session.scans(), 0);
}

#[test]
fn restart_is_time_zero_again() {
    let mut app = app("press.plc.toml");
    auto_at_the_top(&mut app);
    let st = call(&mut app, "POST", "/api/restart", "{}");
    assert_eq!(st["scan"], 0);
    assert_eq!(st["supervisors"][0]["name"], "1");
    assert_eq!(
        st["inputs"],
        serde_json::json!([false, false, false, false, false, false])
    );
    assert!(st["log"].as_array().unwrap().is_empty());
    assert_eq!(
        app.session.inputs_csv().unwrap().lines().count(),
        1,
        "only the header"
    );
}

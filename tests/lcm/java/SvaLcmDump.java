// Decodes an LCM log with the Java types lcm-gen makes from port/lcm/types (the jar
// that lcm-spy needs on its class path) and prints one JSON object per event of the
// channels PREFIX{FLEET,MISSION,PLAN,STATUS}. test_netns.py compares the output with
// what the C node published and the Python ground tool decoded.
//
//   java -cp lcm.jar:sva_lcm.jar:. SvaLcmDump LOG PREFIX
//
// Exit 0 when every event of those channels decoded (fingerprint and size included),
// 1 when one did not (its line then carries "error"), 2 on bad arguments.
import java.io.EOFException;
import java.io.IOException;

import lcm.logging.Log;
import sva_lcm.fleet_state_t;
import sva_lcm.frame_t;
import sva_lcm.mission_t;
import sva_lcm.node_status_t;
import sva_lcm.plan_t;
import sva_lcm.route_t;

public final class SvaLcmDump {
    private SvaLcmDump() {}

    private static String ints(int[] a, int n) {
        StringBuilder b = new StringBuilder("[");
        for (int i = 0; i < n; i++) {
            b.append(i == 0 ? "" : ", ").append(a[i]);
        }
        return b.append("]").toString();
    }

    private static String plan(plan_t p) {
        StringBuilder b = new StringBuilder();
        b.append("\"plan_id\": ").append(p.plan_id)
         .append(", \"version\": ").append(p.version)
         .append(", \"fleet_revision\": ").append(p.fleet_revision)
         .append(", \"mission_revision\": ").append(p.mission_revision)
         .append(", \"algorithm\": ").append(p.algorithm)
         .append(", \"status\": ").append(p.status)
         .append(", \"covered\": ").append(p.covered)
         .append(", \"cost\": ").append(p.cost)
         .append(", \"has_bound\": ").append(p.has_bound)
         .append(", \"lower_bound\": ").append(p.lower_bound)
         .append(", \"optimal\": ").append(p.optimal)
         .append(", \"flow_incomplete\": ").append(p.flow_incomplete)
         .append(", \"uncovered\": ").append(ints(p.uncovered, p.uncovered_count))
         .append(", \"routes\": [");
        int k = 0;
        for (int r = 0; r < p.route_count; r++) {
            route_t rt = p.routes[r];
            int[] ids = new int[rt.target_count];
            for (int j = 0; j < rt.target_count; j++) {
                ids[j] = p.route_targets[k++];
            }
            b.append(r == 0 ? "" : ", ")
             .append("{\"uav\": ").append(rt.uav_id)
             .append(", \"targets\": ").append(ints(ids, ids.length))
             .append(", \"distance\": ").append(rt.distance_cells)
             .append(", \"fuel_used\": ").append(rt.fuel_used)
             .append(", \"stranded\": ").append(rt.stranded).append("}");
        }
        return b.append("]").toString();
    }

    public static void main(String[] args) throws IOException {
        if (args.length != 2) {
            System.err.println("usage: SvaLcmDump LOG PREFIX");
            System.exit(2);
        }
        String prefix = args[1];
        Log log = new Log(args[0], "r");
        int failures = 0;
        while (true) {
            Log.Event e;
            try {
                e = log.readNext();
            } catch (EOFException eof) {
                break;
            }
            if (!e.channel.startsWith(prefix)) {
                continue;
            }
            String kind = e.channel.substring(prefix.length());
            String body;
            try {
                if (kind.equals("FLEET")) {
                    fleet_state_t f = new fleet_state_t(e.data);
                    int[] ids = new int[f.uav_count];
                    for (int i = 0; i < f.uav_count; i++) {
                        ids[i] = f.uavs[i].id;
                    }
                    body = "\"version\": " + f.version + ", \"revision\": " + f.revision
                         + ", \"uavs\": " + ints(ids, ids.length);
                } else if (kind.equals("MISSION")) {
                    mission_t m = new mission_t(e.data);
                    int[] ids = new int[m.target_count];
                    for (int i = 0; i < m.target_count; i++) {
                        ids[i] = m.targets[i].id;
                    }
                    frame_t g = m.frame;
                    body = "\"version\": " + m.version + ", \"revision\": " + m.revision
                         + ", \"targets\": " + ints(ids, ids.length) + ", \"frame\": [" + g.present
                         + ", " + g.lat_e7 + ", " + g.lon_e7 + ", " + g.alt_cm + ", " + g.cell_cm
                         + ", " + g.tick_ms + ", " + g.t0_ms + "]";
                } else if (kind.equals("PLAN")) {
                    body = plan(new plan_t(e.data));
                } else if (kind.equals("STATUS")) {
                    node_status_t s = new node_status_t(e.data);
                    body = "\"version\": " + s.version + ", \"seq\": " + s.seq + ", \"fleet_rx\": " + s.fleet_rx + ", \"mission_rx\": "
                         + s.mission_rx + ", \"plans_published\": " + s.plans_published
                         + ", \"last_plan_id\": " + s.last_plan_id;
                } else {
                    continue;
                }
            } catch (IOException bad) {
                failures++;
                body = "\"error\": \"" + bad.getMessage().replace("\"", "'") + "\"";
            }
            System.out.println("{\"channel\": \"" + kind + "\", \"bytes\": " + e.data.length + ", " + body + "}");
        }
        log.close();
        System.exit(failures == 0 ? 0 : 1);
    }
}

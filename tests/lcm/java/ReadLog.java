// Reads an rtedge LCM log with LCM's Java log reader (lcm.jar) and the
// generated Java types (rtedge-lcmtypes.jar): each message decodes and
// re-encodes to the same bytes.
//   java -cp lcm.jar:rtedge-lcmtypes.jar ReadLog.java LOG
import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.util.Arrays;

import lcm.lcm.LCMDataInputStream;
import lcm.lcm.LCMEncodable;
import lcm.logging.Log;

public class ReadLog {
    static LCMEncodable decode(String channel, byte[] data) throws Exception {
        LCMDataInputStream in = new LCMDataInputStream(data);
        switch (channel) {
        case "LANES": return new rtedge.lane_detection_t(in);
        case "GRASP": return new rtedge.grasp_detection_t(in);
        case "STATUS": return new rtedge.status_t(in);
        case "PARAMS": return new rtedge.params_t(in);
        case "IMAGE": return new rtedge.image_t(in);
        default: throw new Exception("unexpected channel " + channel);
        }
    }

    public static void main(String[] args) throws Exception {
        Log log = new Log(args[0], "r");
        int n = 0;
        while (true) {
            Log.Event ev;
            try {
                ev = log.readNext();
            } catch (java.io.EOFException e) {
                break;
            }
            LCMEncodable m = decode(ev.channel, ev.data);
            if (m instanceof rtedge.lane_detection_t) {
                rtedge.lane_t left = ((rtedge.lane_detection_t) m).left;
                if (left.npoints != 3 || left.points_x.length != rtedge.lane_t.MAX_POINTS ||
                    left.points_y[1] != 690.0f)
                    throw new Exception("LANES: the lane's points are not the sample's");
            }
            if (m instanceof rtedge.grasp_detection_t) {
                rtedge.grasp_object_t o = ((rtedge.grasp_detection_t) m).objects[2];
                if (o.jaw_x.length != 2 || o.jaw_y.length != 2 || o.score != 0.5f)
                    throw new Exception("GRASP: the object's jaws and score are not the sample's");
            }
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            m.encode(new DataOutputStream(bytes));
            if (!Arrays.equals(bytes.toByteArray(), ev.data))
                throw new Exception(ev.channel + ": re-encoding differs");
            n++;
        }
        if (n != 5)
            throw new Exception("expected 5 messages, read " + n);
        System.out.println("java: 5 messages decoded and re-encoded");
    }
}

import java.awt.Component;
import java.awt.Container;
import java.awt.Frame;
import java.awt.Point;
import java.awt.Rectangle;
import java.awt.Robot;
import java.awt.event.InputEvent;
import java.io.File;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.lang.instrument.Instrumentation;
import javax.swing.JTable;
import javax.swing.SwingUtilities;

/**
 * A Java agent in rtedge-spy's JVM (JAVA_TOOL_OPTIONS=-javaagent:probe.jar=OUT,CHANNEL) for
 * tests/lcm/spy.sh: twice a second it writes what the Spy shows to the file OUT: one line per
 * visible window ("window TITLE") and one per row of its tables ("row CELL CELL ...",
 * tab-separated, as displayed: channel, type, messages, ...). Once CHANNEL's row has messages and
 * the table's rows have stayed in the same order for one poll, it double-clicks that row with the
 * mouse (java.awt.Robot, through the X server), as a person opens a channel's viewer, and puts the
 * viewer beside the Spy window for the screenshot. The wait matters: the Spy keeps its rows
 * sorted, so a channel appearing between finding the row and the click would shift the row under
 * the pointer and open another channel's viewer.
 */
public final class SpyProbe {
    private static boolean clicked;
    private static String previousChannels = "";

    public static void premain(String args, Instrumentation inst) {
        String[] a = args.split(",", 2);
        Thread t = new Thread(() -> run(new File(a[0]), a.length > 1 ? a[1] : ""), "spy-probe");
        t.setDaemon(true);
        t.start();
    }

    private static void run(File out, String channel) {
        File tmp = new File(out.getPath() + ".tmp");
        for (;;) {
            try {
                Thread.sleep(500);
                StringWriter text = new StringWriter();
                StringBuilder channels = new StringBuilder();
                Point[] click = new Point[1];
                SwingUtilities.invokeAndWait(() -> dump(new PrintWriter(text), channel, click, channels));
                try (PrintWriter w = new PrintWriter(tmp, "UTF-8")) {
                    w.print(text);
                }
                if (!tmp.renameTo(out)) {
                    throw new IllegalStateException("cannot write " + out);
                }
                boolean steady = channels.toString().equals(previousChannels);
                previousChannels = channels.toString();
                if (click[0] != null && steady && !clicked) {
                    clicked = true;
                    Robot robot = new Robot();
                    robot.mouseMove(click[0].x, click[0].y);
                    for (int i = 0; i < 2; i++) {
                        robot.mousePress(InputEvent.BUTTON1_DOWN_MASK);
                        robot.mouseRelease(InputEvent.BUTTON1_DOWN_MASK);
                    }
                }
            } catch (Exception e) {
                e.printStackTrace();
                return;
            }
        }
    }

    private static void dump(PrintWriter w, String channel, Point[] click, StringBuilder channels) {
        for (Frame f : Frame.getFrames()) {
            if (!f.isShowing()) {
                continue;
            }
            w.println("window\t" + f.getTitle());
            if (f.getTitle().equals(channel) && f.getX() == 0) {
                f.setLocation(810, 0);  // beside the Spy window (no window manager places it)
            }
            tables(w, f, channel, click, channels);
        }
        w.flush();
    }

    private static void tables(PrintWriter w, Container c, String channel, Point[] click,
                               StringBuilder channels) {
        for (Component k : c.getComponents()) {
            if (k instanceof JTable) {
                JTable t = (JTable) k;
                for (int r = 0; r < t.getRowCount(); r++) {
                    StringBuilder line = new StringBuilder("row");
                    for (int col = 0; col < t.getColumnCount(); col++) {
                        line.append('\t').append(t.getValueAt(r, col));
                    }
                    w.println(line);
                    channels.append(t.getValueAt(r, 0)).append('\n');
                    Object messages = t.getColumnCount() > 2 ? t.getValueAt(r, 2) : null;
                    if (channel.equals(String.valueOf(t.getValueAt(r, 0))) && messages != null
                        && !"0".equals(messages.toString().trim())) {
                        Rectangle cell = t.getCellRect(r, 0, true);
                        Point p = t.getLocationOnScreen();
                        click[0] = new Point(p.x + cell.x + cell.width / 2, p.y + cell.y + cell.height / 2);
                    }
                }
            } else if (k instanceof Container) {
                tables(w, (Container) k, channel, click, channels);
            }
        }
    }
}
